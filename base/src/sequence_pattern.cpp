// Sequence patterns, parsed and formatted without printf (sequence_pattern.hpp).
#include "nimbus/base/sequence_pattern.hpp"

#include <stdexcept>

#include "nimbus/base/input_limits.hpp"

namespace nimbus {

SequencePattern SequencePattern::parse(const std::string& text, const std::string& what) {
  SequencePattern p;
  const std::size_t field = text.find('%');
  if (field == std::string::npos) {
    p.head = text;
    return p;
  }
  const auto refuse = [&](const std::string& why) {
    throw std::invalid_argument(what + " '" + echo(text) + "': " + why);
  };
  // %d, or %0 followed by one digit 1-9 and d.
  std::size_t end = field + 1;
  int width = 0;
  if (end < text.size() && text[end] == '0') {
    ++end;
    if (end < text.size() && text[end] >= '1' && text[end] <= '9') width = text[end++] - '0';
    else refuse("a frame field is %d or %0Nd with N from 1 to 9 (such as %04d)");
  }
  if (end >= text.size() || text[end] != 'd')
    refuse("a frame field is %d or %0Nd with N from 1 to 9 (such as %04d), and no other % may appear");
  p.head = text.substr(0, field);
  p.tail = text.substr(end + 1);
  if (p.tail.find('%') != std::string::npos) refuse("holds more than one %: a name has at most one frame field");
  p.width = width;
  p.has_field = true;
  return p;
}

std::string frame_number_text(long frame, int width) {
  const bool negative = frame < 0;
  // The magnitude as an unsigned value: -LONG_MIN does not fit a long.
  unsigned long m = negative ? 0ul - static_cast<unsigned long>(frame) : static_cast<unsigned long>(frame);
  std::string digits;
  do {
    digits.insert(digits.begin(), static_cast<char>('0' + m % 10));
    m /= 10;
  } while (m);
  const std::size_t sign = negative ? 1 : 0;
  if (digits.size() + sign < static_cast<std::size_t>(width)) digits.insert(0, width - sign - digits.size(), '0');
  return (negative ? "-" : "") + digits;
}

std::string SequencePattern::path(long frame) const {
  return has_field ? head + frame_number_text(frame, width) + tail : head;
}

}  // namespace nimbus
