// A point of flat texture space: s left to right, t bottom to top; the texture's square is
// [0, 1] x [0, 1].
#pragma once

namespace tessera {

struct TexCoord {
  double s = 0, t = 0;
  friend bool operator==(const TexCoord&, const TexCoord&) = default;
};

}  // namespace tessera
