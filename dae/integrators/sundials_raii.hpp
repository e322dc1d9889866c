#pragma once
/// One RAII owner per SUNDIALS object shared by the integrators (IDA, CVODE), and the Eigen view of
/// an N_Vector's data (wrapped, never copied). SUNDIALS types stay inside dae/.

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nonlinearsolver.h>
#include <Eigen/Dense>
#include <cstdlib>
#include <memory>
#include <string>
#include <type_traits>

namespace condyn::sundials {

struct ContextDeleter {
  void operator()(SUNContext ctx) const { SUNContext_Free(&ctx); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct SolverDeleter {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
struct NonlinearSolverDeleter {
  void operator()(SUNNonlinearSolver s) const { SUNNonlinSolFree(s); }
};
using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using SolverPtr = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, SolverDeleter>;
using NonlinearSolverPtr =
    std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, NonlinearSolverDeleter>;

inline Eigen::Map<Eigen::VectorXd> view(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

/// The name of a return flag from IDAGetReturnFlagName / CVodeGetReturnFlagName, which return a
/// string the caller must free (SUNDIALS allocates it with malloc): copied, then freed.
inline std::string flag_name(char* (*get_name)(long int), int flag) {
  const std::unique_ptr<char, decltype(&std::free)> name(get_name(flag), &std::free);
  return name ? std::string(name.get()) : "flag " + std::to_string(flag);
}

}  // namespace condyn::sundials
