// The file names of a numbered sequence ("cloud.%04d.vdb"), parsed once into a checked form. The
// only field is %d or %0Nd (N from 1 to 9), at most one, and no other '%'; names are made here by
// formatting the number, so no text a user wrote is ever handed to printf as a format.
#pragma once
#include <string>

namespace nimbus {

struct SequencePattern {
  std::string head, tail;  // the text before and after the frame field
  int width = 0;           // %0Nd: at least N characters, zero-padded (the sign counts, as printf's); %d: 0
  bool has_field = false;  // false: the text holds no '%' and names one file

  // std::invalid_argument "<what> '<text, echoed>': ..." when `text` holds a '%' that is not one
  // %d or %0Nd field with N <= 9, or more than one field.
  static SequencePattern parse(const std::string& text, const std::string& what);

  // The name of `frame`: head + the number (zero-padded to `width`) + tail. A pattern without a
  // field names the same file for every frame.
  std::string path(long frame) const;
};

// `frame` as %0Nd writes it: "-005" for -5 at width 4, "12345" for 12345 at width 4.
std::string frame_number_text(long frame, int width);

}  // namespace nimbus
