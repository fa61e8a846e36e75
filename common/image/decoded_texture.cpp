#include "common/image/decoded_texture.h"

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace tessera {

namespace {

constexpr std::string_view kMagic = "TSTEX01\n";
constexpr std::size_t kHeaderSize = kMagic.size() + 4 + 4 + 1 + 1;
enum SampleKind : std::uint8_t { kEightBit = 0, kFloat32 = 1 };

struct Header {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  int source_channels = 0;
  SampleKind kind = kEightBit;
};

void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

std::uint32_t get_u32(std::string_view bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i)
    v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + i])) << (8 * i);
  return v;
}

[[noreturn]] void malformed(const std::string& name, const std::string& why) {
  throw std::runtime_error("cannot read " + name + ": not a well-formed decoded texture (" + why +
                           ")");
}

Header read_header(std::string_view bytes, const std::string& name) {
  if (!is_decoded_texture(bytes) || bytes.size() < kHeaderSize) malformed(name, "short header");
  Header h;
  h.width = get_u32(bytes, kMagic.size());
  h.height = get_u32(bytes, kMagic.size() + 4);
  h.source_channels = static_cast<unsigned char>(bytes[kMagic.size() + 8]);
  const auto kind = static_cast<unsigned char>(bytes[kMagic.size() + 9]);
  if (h.width == 0 || h.height == 0) malformed(name, "no pixels");
  if (h.source_channels < 1 || h.source_channels > 4) malformed(name, "channel count");
  if (kind != kEightBit && kind != kFloat32) malformed(name, "sample kind");
  h.kind = static_cast<SampleKind>(kind);
  return h;
}

// An 8-bit sample as OpenImageIO turns it into a float: k times the float nearest 1/255 (which
// differs from k / 255.0f in the last bit for about half of the values).
float eight_bit_float(int k) { return static_cast<float>(k) * (1.0f / 255.0f); }

// The integer k with eight_bit_float(k) == v exactly, or -1.
int eight_bit_value(float v) {
  if (!(v >= 0.0f && v <= 1.0f)) return -1;
  const int k = static_cast<int>(v * 255.0f + 0.5f);
  return eight_bit_float(k) == v ? k : -1;
}

std::string deflate(const std::string& raw) {
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string out(size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(out.data()), &size,
                reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size()),
                Z_BEST_SPEED) != Z_OK)
    throw std::runtime_error("cannot compress a decoded texture");
  out.resize(size);
  return out;
}

}  // namespace

bool is_decoded_texture(std::string_view bytes) { return bytes.starts_with(kMagic); }

std::string encode_decoded_texture(const Image& image, int source_channels) {
  bool eight_bit = true;
  for (float v : image.rgb) eight_bit = eight_bit && eight_bit_value(v) >= 0;
  std::string samples;
  if (eight_bit) {
    samples.reserve(image.rgb.size());
    for (float v : image.rgb) samples.push_back(static_cast<char>(eight_bit_value(v)));
  } else {
    samples.resize(image.rgb.size() * sizeof(float));
    // Little-endian hosts only (x86-64, AArch64), as the frame buffer's float payloads.
    std::memcpy(samples.data(), image.rgb.data(), samples.size());
  }
  std::string out(kMagic);
  put_u32(out, static_cast<std::uint32_t>(image.width));
  put_u32(out, static_cast<std::uint32_t>(image.height));
  out.push_back(static_cast<char>(source_channels));
  out.push_back(static_cast<char>(eight_bit ? kEightBit : kFloat32));
  return out + deflate(samples);
}

Image decode_decoded_texture(std::string_view bytes, const std::string& name,
                             std::size_t max_pixels) {
  const Header h = read_header(bytes, name);
  const std::size_t pixels = static_cast<std::size_t>(h.width) * h.height;
  if (pixels > max_pixels)
    throw std::runtime_error("cannot read " + name + ": " + std::to_string(h.width) + "x" +
                             std::to_string(h.height) + " pixels is more than " +
                             std::to_string(max_pixels));
  const std::size_t sample_bytes = h.kind == kEightBit ? 1 : sizeof(float);
  std::vector<unsigned char> samples(pixels * 3 * sample_bytes);
  uLongf size = static_cast<uLongf>(samples.size());
  const std::string_view packed = bytes.substr(kHeaderSize);
  if (uncompress(samples.data(), &size, reinterpret_cast<const Bytef*>(packed.data()),
                 static_cast<uLong>(packed.size())) != Z_OK ||
      size != samples.size())
    malformed(name, "samples do not inflate to " + std::to_string(h.width) + "x" +
                        std::to_string(h.height) + " pixels");
  Image image(static_cast<int>(h.width), static_cast<int>(h.height));
  if (h.kind == kEightBit) {
    for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = eight_bit_float(samples[i]);
  } else {
    std::memcpy(image.rgb.data(), samples.data(), samples.size());
  }
  return image;
}

int decoded_texture_channels(std::string_view bytes, const std::string& name) {
  return read_header(bytes, name).source_channels;
}

Image decode_texture(std::string_view bytes, const std::string& name, std::size_t max_pixels) {
  return is_decoded_texture(bytes) ? decode_decoded_texture(bytes, name, max_pixels)
                                   : decode_image(bytes, name, max_pixels);
}

int texture_channels(std::string_view bytes, const std::string& name) {
  return is_decoded_texture(bytes) ? decoded_texture_channels(bytes, name)
                                   : image_channels(bytes, name);
}

std::size_t texture_pixels(std::string_view bytes, const std::string& name) {
  if (!is_decoded_texture(bytes)) return image_pixels(bytes, name);
  const Header h = read_header(bytes, name);
  return static_cast<std::size_t>(h.width) * h.height;
}

}  // namespace tessera
