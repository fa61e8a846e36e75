#include "common/image/exr/encode_exr.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cstring>
#include <exception>
#include <stdexcept>

namespace tessera {

namespace {

// OpenEXR writes the scan lines, then seeks back to fill in their offsets: a string that grows
// as it is written at any position.
class StringStream : public Imf::OStream {
 public:
  explicit StringStream(std::string& out) : Imf::OStream("memory"), out_(out) {}
  void write(const char c[], int n) override {
    const auto count = static_cast<std::size_t>(n);
    if (position_ + count > out_.size()) out_.resize(position_ + count);
    std::memcpy(out_.data() + position_, c, count);
    position_ += count;
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t position) override { position_ = static_cast<std::size_t>(position); }

 private:
  std::string& out_;
  std::size_t position_ = 0;
};

}  // namespace

std::string encode_exr(const Image& image) {
  std::string out;
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    // OpenEXR reads from the frame buffer only; its slices take non-const pointers.
    char* base = const_cast<char*>(reinterpret_cast<const char*>(image.rgb.data()));
    const std::size_t pixel = 3 * sizeof(float),
                      row = pixel * static_cast<std::size_t>(image.width);
    Imf::FrameBuffer frame;
    const char* names[] = {"R", "G", "B"};
    for (std::size_t c = 0; c < 3; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), pixel, row));
    }
    StringStream stream(out);
    Imf::OutputFile file(stream, header);  // its destructor writes the offsets
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("encoding exr: ") + e.what());
  }
  return out;
}

}  // namespace tessera
