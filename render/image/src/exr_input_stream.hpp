// The OpenEXR input stream read_exr reads through: a regular file, opened without blocking and
// checked on the descriptor that was opened (read_exr refuses a FIFO, directory or device by its
// name before, but the name may point elsewhere by now). Reads with pread at the stream's own
// position, so the header check (exr_header_check.hpp) and OpenEXR read the same bytes of the same
// file, whose size at opening bounds what its header may declare.
#pragma once
#include <OpenEXR/ImfIO.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace nimbus::render {

class ExrInputStream : public Imf::IStream {
 public:
  // std::runtime_error without the path (read_exr adds it) when the file cannot be opened or is
  // not a regular file.
  explicit ExrInputStream(const std::string& path);
  ~ExrInputStream() override;
  ExrInputStream(const ExrInputStream&) = delete;
  ExrInputStream& operator=(const ExrInputStream&) = delete;

  // The file's size when it was opened, bytes: what the header's claims are checked against.
  std::uint64_t size() const { return size_; }
  // Reads up to n bytes at `pos` into `out`; fewer only at the end of the file. std::runtime_error
  // on a read error (OpenEXR passes on any exception its stream throws: catch (...) { throw; }).
  std::size_t read_at(std::uint64_t pos, char* out, std::size_t n) const;

  // Imf::IStream (ImfIO.h): read throws when fewer than n bytes are left and returns false once
  // the last byte was read.
  bool read(char c[], int n) override;
  std::uint64_t tellg() override { return pos_; }
  void seekg(std::uint64_t pos) override { pos_ = pos; }

 private:
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::uint64_t pos_ = 0;
};

}  // namespace nimbus::render
