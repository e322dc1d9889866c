#pragma once
/// What the program prints carries no control sequence that came from its input.
///
/// A scene's file name, a flag's value or a line quoted from a file may hold control characters:
/// an escape sequence would recolour, retitle or clear the user's terminal, a carriage return
/// would hide what came before it on the line. Rather than escape every place that names a file
/// (there are hundreds of messages), the program routes std::cout and std::cerr once through
/// EscapingStreambuf, which shows such bytes as \xNN. Line feeds and tabs pass. Results written
/// to standard output (`--out -`) go to the descriptor, not through std::cout, and are unchanged.

#include <streambuf>

namespace condyn {

/// Forwards to `sink` all but C0 control characters other than line feed and tab, DEL, and the
/// UTF-8 encodings of C1 controls (U+0080 to U+009F) and stray bytes 0x80 to 0x9F outside a UTF-8
/// sequence (8-bit terminals read those as C1 controls): those become the text \xNN (\xc2\x9b
/// for U+009B). A failed write to `sink` fails this buffer's stream.
class EscapingStreambuf : public std::streambuf {
 public:
  explicit EscapingStreambuf(std::streambuf* sink) : sink_(sink) {}

 protected:
  int_type overflow(int_type c) override;
  std::streamsize xsputn(const char* s, std::streamsize n) override;
  int sync() override;

 private:
  /// Writes s[0, n) as it is; false when the sink took less.
  bool pass(const char* s, std::streamsize n);
  /// Writes `c` as \xNN (after a held 0xC2, as \xc2\xNN).
  bool escape(unsigned char c);
  /// How many leading bytes of s[0, n) pass unchanged, updating the UTF-8 state.
  std::streamsize passing_run(const char* s, std::streamsize n);

  std::streambuf* sink_;
  int continuation_ = 0;  ///< UTF-8 continuation bytes still expected
  bool held_c2_ = false;  ///< a 0xC2 lead byte not yet written: U+0080..U+009F would follow
};

/// Routes std::cout and std::cerr through an EscapingStreambuf each, for the rest of the process.
void escape_standard_streams();

}  // namespace condyn
