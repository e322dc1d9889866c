# Fails the build when a source file names one of the Eigen decompositions that
# models/core/eigen_decompositions.hpp declares compiled once, without including that header: the
# file would compile its own copy (correct, but up to a minute of compiler time per file under the
# sanitizers). Run at every build by the target condyn_layers (CMakeLists.txt).
#   cmake -DROOT=<checkout> -P scripts/check_eigen_instances.cmake
set(header "models/core/eigen_decompositions.hpp")
# The class names, and the MatrixBase functions that return one of them.
set(names "BDCSVD|JacobiSVD|ColPivHouseholderQR|HouseholderQR|FullPivLU|PartialPivLU"
          "|SelfAdjointEigenSolver|LLT<|LDLT<|SparseLU|SimplicialLDLT|bdcSvd|jacobiSvd"
          "|colPivHouseholderQr|householderQr|fullPivLu|partialPivLu|\\.lu\\(\\)|\\.llt\\(\\)"
          "|\\.ldlt\\(\\)")
string(CONCAT names ${names})
set(bad "")
foreach(top src dae models validation tests python bench)
  file(GLOB_RECURSE files ${ROOT}/${top}/*.cpp ${ROOT}/${top}/*.hpp)
  foreach(file IN LISTS files)
    file(RELATIVE_PATH rel ${ROOT} ${file})
    if(rel STREQUAL header OR rel STREQUAL "models/core/eigen_decompositions.cpp")
      continue()
    endif()
    file(STRINGS ${file} uses REGEX "(${names})" LIMIT_COUNT 1)
    if(NOT uses)
      continue()
    endif()
    file(STRINGS ${file} included REGEX "^#include \"${header}\"")
    if(NOT included)
      string(STRIP "${uses}" line)
      string(REPLACE "\\;" ";" line "${line}")
      string(APPEND bad "\n  ${rel}: ${line}")
    endif()
  endforeach()
endforeach()
if(bad)
  message(FATAL_ERROR "these files use an Eigen decomposition without #include \"${header}\", "
                      "which compiles it once for all (its comment says why):${bad}")
endif()
