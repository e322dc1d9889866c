#pragma once
/// condyn's own operations for SUNDIALS' serial N_Vector (issue 12).
///
/// Debian 12's SUNDIALS 6.4 packages are built without optimization: the serial vector's
/// operations compile to -O0 code (objdump of libsundials_ida.so.6.4.1 and
/// libsundials_nvecserial.so.6.4.1: every local on the stack), about 20 to 30 instructions per
/// entry, and they are a large part of a step's instructions on large models (docs/benchmarks.md,
/// from callgrind). SUNDIALS lets a program set a vector's operation
/// table: these are the same operations, compiled with the project's optimization, the
/// fused ones (linear combinations, vector arrays) included so that IDA's predictor reads each
/// vector once. Written here because no Debian package has an optimized build of them.
///
/// Not threaded: the operations are bound by memory bandwidth, and OpenMP over two threads did not
/// shorten a large GGL step (docs/benchmarks.md).
///
/// Vectors cloned from one that has these operations have them too (N_VClone copies the table).

#include <sundials/sundials_nvector.h>

namespace condyn::sundials {

/// Sets the operations of `v`, a serial vector (SUNDIALS_NVEC_SERIAL; else std::invalid_argument).
void use_condyn_vector_ops(N_Vector v);

/// A new serial vector of length n with these operations (the integrators' y, y', id and work
/// vectors); null when SUNDIALS cannot allocate it.
[[nodiscard]] N_Vector new_vector(sunindextype n, SUNContext ctx);

}  // namespace condyn::sundials
