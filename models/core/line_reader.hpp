#pragma once
/// The line reading shared by the text formats condyn reads (Matrix Market, time tables): the
/// line endings and byte order mark that editors and spreadsheets write, and the line numbers
/// their messages name.

#include <cstddef>
#include <istream>
#include <string>
#include <string_view>

namespace condyn {

/// Serves the lines of a stream one at a time, never holding more than one line of it (a stiffness
/// file of a million DOFs is 300 MB of text). A line ends in LF, CRLF or a lone CR (the classic Mac
/// ending some spreadsheets still write); a UTF-8 byte order mark at the start of the first line
/// (Windows editors and spreadsheets write one) is no part of it.
class LineReader {
 public:
  explicit LineReader(std::istream& in) : in_(&in) {}
  /// The next line without its ending, valid until the next call; false at the end of the text.
  bool next(std::string_view& line);
  /// The 1-based number of the line last served (0 before the first), for messages.
  [[nodiscard]] int line_number() const { return line_number_; }
  /// Whether the stream failed to read (an I/O error, not the end of the text).
  [[nodiscard]] bool failed() const { return in_->bad(); }

 private:
  std::istream* in_;
  std::string buffer_;    // what getline read up to an LF, served in parts at each CR inside it
  std::size_t at_ = 0;    // where the next part of buffer_ starts
  bool serving_ = false;  // whether buffer_ holds parts not yet served
  int line_number_ = 0;
};

}  // namespace condyn
