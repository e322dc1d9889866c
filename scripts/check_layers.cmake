# Fails when a source file includes a header from a layer above its own. The layers, lowest first
# (docs/contributing.md, "Where code lives"):
#   models/core <- models/systems, models/scene <- models/assembly
#   <- dae/linsolve <- dae/interface <- dae/integrators <- dae/formulations <- dae/run
#   <- validation/references <- validation/studies <- src/output <- src/reports <- src/cli
# Folders on one level (systems and scene) may not include each other. The solver (dae/) sees of
# models/ only core: the Model, its run settings (SolveSpec), the MechanicalSystem interface; never
# the scene format, the builder or the concrete systems (the pairs in `apart`), so that editing the
# format or a body type recompiles no integrator. Run by the build (target condyn_layers):
#   cmake -DROOT=<source dir> -P scripts/check_layers.cmake
cmake_policy(SET CMP0057 NEW)
set(levels
    "models/core" "models/systems|models/scene" "models/assembly"
    "dae/linsolve" "dae/interface" "dae/integrators" "dae/formulations" "dae/run"
    "validation/references" "validation/studies" "src/output" "src/reports" "src/cli")
# Lower folders a library may not include: "LIBRARY>FOLDER".
set(apart "dae>models/scene" "dae>models/assembly" "dae>models/systems")
# Includes that still run up a level, each with the change that removes it (issue 43):
#   none left; a new one names its header pair here, "FILE>HEADER".
set(known_exceptions "")

# The level of a folder such as "dae/run", or -1 when it has none.
function(level_of folder out)
  set(index 0)
  foreach(level IN LISTS levels)
    string(REPLACE "|" ";" members "${level}")
    if(folder IN_LIST members)
      set(${out} ${index} PARENT_SCOPE)
      return()
    endif()
    math(EXPR index "${index} + 1")
  endforeach()
  set(${out} -1 PARENT_SCOPE)
endfunction()

set(bad "")
foreach(top models dae validation src)
  file(GLOB stray ${ROOT}/${top}/*.cpp ${ROOT}/${top}/*.hpp)
  foreach(file IN LISTS stray)
    file(RELATIVE_PATH rel ${ROOT} ${file})
    string(APPEND bad "\n  ${rel}: a source file outside the layer folders of ${top}/")
  endforeach()
endforeach()
foreach(level IN LISTS levels)
  string(REPLACE "|" ";" members "${level}")
  foreach(folder IN LISTS members)
    level_of(${folder} own)
    file(GLOB files ${ROOT}/${folder}/*.cpp ${ROOT}/${folder}/*.hpp)
    foreach(file IN LISTS files)
      file(RELATIVE_PATH rel ${ROOT} ${file})
      file(STRINGS ${file} includes REGEX "^#include \"[a-z_]+/")
      foreach(line IN LISTS includes)
        string(REGEX REPLACE "^#include \"([a-z_]+/[a-z_]+)/.*" "\\1" target "${line}")
        string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" header "${line}")
        if(target STREQUAL folder OR "${rel}>${header}" IN_LIST known_exceptions)
          continue()
        endif()
        level_of(${target} level)
        string(REGEX REPLACE "/.*" "" library "${folder}")
        if(level EQUAL -1)
          string(APPEND bad "\n  ${rel}: ${line} (not a header of a layer folder)")
        elseif(NOT level LESS own)
          string(APPEND bad "\n  ${rel}: ${line} (${folder} may include only layers below it)")
        elseif("${library}>${target}" IN_LIST apart)
          string(APPEND bad "\n  ${rel}: ${line} (${library}/ may not include ${target}/)")
        endif()
      endforeach()
    endforeach()
  endforeach()
endforeach()
if(bad)
  message(FATAL_ERROR "include up the layers (scripts/check_layers.cmake lists them):${bad}")
endif()
