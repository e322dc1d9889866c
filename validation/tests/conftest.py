"""The figure scripts' tests (ctest label plots): imported from validation/, the condyn binary
from CONDYN_BINARY (set by CMake)."""
import os
import sys

import matplotlib

matplotlib.use("Agg")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
