#include "src/output/escaped_streams.hpp"

#include <array>
#include <iostream>

namespace condyn {

namespace {

bool is_c0_control(unsigned char u) { return (u < 0x20 && u != '\n' && u != '\t') || u == 0x7f; }

}  // namespace

bool EscapingStreambuf::pass(const char* s, std::streamsize n) {
  return n == 0 || sink_->sputn(s, n) == n;
}

bool EscapingStreambuf::escape(unsigned char c) {
  constexpr char kHex[] = "0123456789abcdef";
  std::array<char, 8> text{};
  std::streamsize n = 0;
  if (held_c2_) {
    for (const char k : {'\\', 'x', 'c', '2'}) text[n++] = k;
    held_c2_ = false;
  }
  for (const char k : {'\\', 'x', kHex[c >> 4], kHex[c & 0xf]}) text[n++] = k;
  continuation_ = 0;
  return pass(text.data(), n);
}

std::streamsize EscapingStreambuf::passing_run(const char* s, std::streamsize n) {
  std::streamsize i = 0;
  for (; i < n; ++i) {
    const auto u = static_cast<unsigned char>(s[i]);
    if (u < 0x80) {
      if (is_c0_control(u)) break;
      continuation_ = 0;
    } else if (u < 0xc0) {  // a continuation byte: C1 when no sequence expects it
      if (continuation_ == 0 && u < 0xa0) break;
      if (continuation_ > 0) --continuation_;
    } else if (u == 0xc2) {  // may open U+0080..U+009F: decided by the next byte
      break;
    } else {
      continuation_ = u < 0xe0 ? 1 : u < 0xf0 ? 2 : u < 0xf8 ? 3 : 0;
    }
  }
  return i;
}

std::streamsize EscapingStreambuf::xsputn(const char* s, std::streamsize n) {
  std::streamsize done = 0;
  while (done < n) {
    const auto u = static_cast<unsigned char>(s[done]);
    if (held_c2_) {
      if (u >= 0x80 && u < 0xa0) {
        if (!escape(u)) return done;
        ++done;
        continue;
      }
      held_c2_ = false;
      continuation_ = 1;
      if (!pass("\xc2", 1)) return done;
    }
    if (u == 0xc2) {
      held_c2_ = true;
      ++done;
      continue;
    }
    const std::streamsize run = passing_run(s + done, n - done);
    if (run > 0) {
      if (!pass(s + done, run)) return done;
      done += run;
      continue;
    }
    if (!escape(u)) return done;
    ++done;
  }
  return done;
}

EscapingStreambuf::int_type EscapingStreambuf::overflow(int_type c) {
  if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
  const char ch = traits_type::to_char_type(c);
  return xsputn(&ch, 1) == 1 ? c : traits_type::eof();
}

int EscapingStreambuf::sync() {
  // A held 0xC2 stays held: its next byte decides how it is shown.
  return sink_->pubsync();
}

void escape_standard_streams() {
  // Never destroyed: the streams are flushed at exit, after main's locals are gone.
  static auto* const out = new EscapingStreambuf(std::cout.rdbuf());
  static auto* const err = new EscapingStreambuf(std::cerr.rdbuf());
  std::cout.rdbuf(out);
  std::cerr.rdbuf(err);
}

}  // namespace condyn
