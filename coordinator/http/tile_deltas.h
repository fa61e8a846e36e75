// The body of GET /api/jobs/{id}/tiles?since=N (docs/SERVICE.md, "Tiles"): the units merged
// since the N-th, with the 8-bit values the page paints, in a small binary format. Little-endian
// throughout.
//
//   header, 16 bytes:  "TSD1", u32 next, u32 count, u32 flags
//                      (flags bit 0 "whole": the page must load the whole image, the records
//                      carry no pixels; bit 1 "finished": no record will follow)
//   count records, each 32 bytes and then 3 bytes per pixel:
//     u16 x0, y0, x1, y1   the unit's rectangle, [x0, x1) x [y0, y1)
//     u16 step             the block side: the unit's pixels are the multiples of step in
//                          the rectangle, scanline order, each standing for its block
//     u8 level, u8 pass    level 1..L, or 0 for a whole-image pass; the sample pass
//     u8 flags             bit 0: skips pixels whose x and y are both multiples of 2 step
//                          (the coarser levels' anchors); bit 1: an area preview
//     u8 reserved (0)
//     u16 stage            the row of the job's levels_table
//     u32 worker           the worker that rendered it (GET /api/workers ids)
//     u32 pixels           the number of pixels whose values follow (0 when "whole")
//     f64 merged_at_ms     when the coordinator merged it, milliseconds since 1970
//     pixels x 3 bytes     R, G, B of each pixel as a PNG stores it, each byte the difference
//                          from the same channel of the previous pixel (mod 256)
#pragma once

#include <cstddef>
#include <string>

#include "coordinator/jobs/job.h"

namespace tessera {

// Pixel bytes per answer: beyond it the answer stops early (its `next` says where), so one
// request never makes the io thread convert, copy or compress much.
inline constexpr std::size_t kTilesAnswerBytes = 256u << 10;

std::string encode_tiles(const Job& job, std::size_t since);

}  // namespace tessera
