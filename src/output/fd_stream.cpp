#include "src/output/fd_stream.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <ostream>
#include <streambuf>
#include <vector>

namespace condyn {

namespace {

/// A stream buffer over a file descriptor: what the CSV writers write into, whether the target
/// is a temporary file, a device, a FIFO or standard output.
class FdBuf : public std::streambuf {
 public:
  FdBuf(int fd, bool owned) : fd_(fd), owned_(owned), buffer_(std::size_t{1} << 16) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }
  ~FdBuf() override {
    if (owned_ && fd_ >= 0) ::close(fd_);
  }
  FdBuf(const FdBuf&) = delete;
  FdBuf& operator=(const FdBuf&) = delete;

  /// Flushes and, when owned, closes: 0 on success, else the errno of the first failure.
  int finish() {
    if (!drain() && error_ == 0) error_ = EIO;
    if (owned_ && fd_ >= 0) {
      if (::close(fd_) != 0 && error_ == 0) error_ = errno;
      fd_ = -1;
    }
    return error_;
  }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    if (error_ != 0) return false;
    const char* p = pbase();
    while (p < pptr()) {
      const ssize_t n = ::write(fd_, p, static_cast<std::size_t>(pptr() - p));
      if (n < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        return false;
      }
      p += n;
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return true;
  }

  int fd_;
  bool owned_;
  int error_ = 0;
  std::vector<char> buffer_;
};

}  // namespace

/// Runs `writer` into `fd`; returns 0 or the errno of the failure.
int write_into(int fd, bool owned, const OutputPlan::Writer& writer) {
  FdBuf buf(fd, owned);
  std::ostream out(&buf);
  writer(out);
  out.flush();
  const int error = buf.finish();
  return error != 0 ? error : (out ? 0 : EIO);
}

}  // namespace condyn
