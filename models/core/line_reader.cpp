#include "models/core/line_reader.hpp"

namespace condyn {

bool LineReader::next(std::string_view& line) {
  if (!serving_) {
    if (!std::getline(*in_, buffer_)) return false;
    at_ = 0;
    serving_ = true;
  }
  const auto cr = buffer_.find('\r', at_);
  if (cr == std::string::npos || cr + 1 == buffer_.size()) {  // the last part (CRLF: its CR)
    line = std::string_view(buffer_).substr(at_,
                                            (cr == std::string::npos ? buffer_.size() : cr) - at_);
    serving_ = false;
  } else {
    line = std::string_view(buffer_).substr(at_, cr - at_);
    at_ = cr + 1;
  }
  ++line_number_;
  if (line_number_ == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);
  return true;
}

}  // namespace condyn
