#pragma once
/// Writing an output into a file descriptor: a temporary file, a device, a FIFO or standard
/// output (internal to src/).

#include "src/output/output_files.hpp"

namespace condyn {

/// Runs `writer` into `fd` through a buffer of its own, then flushes it and, when `owned`, closes
/// `fd`; returns 0 or the errno of the first failure (EIO when the writer left the stream failed).
[[nodiscard]] int write_into(int fd, bool owned, const OutputPlan::Writer& writer);

}  // namespace condyn
