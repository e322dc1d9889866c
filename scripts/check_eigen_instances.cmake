# Fails the build when a source file names one of the Eigen decompositions that
# models/core/eigen_decompositions.hpp declares compiled once, without including that header: the
# file would compile its own copy (correct, but up to a minute of compiler time per file under the
# sanitizers). Run at every build by the target condyn_layers (CMakeLists.txt).
#   cmake -DROOT=<checkout> -P scripts/check_eigen_instances.cmake
set(header "models/core/eigen_decompositions.hpp")
# The class names, and the MatrixBase functions that return one of them.
# (PartialPivLU is not among them: condyn uses it only on fixed-size matrices, cheap to compile.)
set(names "ColPivHouseholderQR|HouseholderQR|FullPivLU"
          "|SelfAdjointEigenSolver|LLT<|LDLT<|SparseLU|SimplicialLDLT"
          "|colPivHouseholderQr|householderQr|fullPivLu|\\.llt\\(\\)"
          "|\\.ldlt\\(\\)")
string(CONCAT names ${names})
# Eigen's SVDs, the costliest of all to compile (BDCSVD alone 36 s of g++ -O3), are not used:
# singular values come from LAPACK (models/core/singular_values.hpp).
set(svds "BDCSVD|JacobiSVD|bdcSvd|jacobiSvd|\\.svd\\(")
set(bad "")
set(bad_svd "")
foreach(top src dae models validation tests python bench)
  file(GLOB_RECURSE files ${ROOT}/${top}/*.cpp ${ROOT}/${top}/*.hpp)
  foreach(file IN LISTS files)
    file(RELATIVE_PATH rel ${ROOT} ${file})
    file(STRINGS ${file} svd_uses REGEX "(${svds})" LIMIT_COUNT 1)
    if(svd_uses)
      string(STRIP "${svd_uses}" line)
      string(APPEND bad_svd "\n  ${rel}: ${line}")
    endif()
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
if(bad_svd)
  message(FATAL_ERROR "these files use one of Eigen's SVDs, which costs up to a minute of compiler "
                      "time per file: call condyn::singular_values "
                      "(models/core/singular_values.hpp):${bad_svd}")
endif()
if(bad)
  message(FATAL_ERROR "these files use an Eigen decomposition without #include \"${header}\", "
                      "which compiles it once for all (its comment says why):${bad}")
endif()
