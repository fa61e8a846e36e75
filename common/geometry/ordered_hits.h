// The two questions asked of a shape (its nearest hit; all its crossings, for boolean objects),
// answered from one routine that hands its hits over in ascending order: visit(take) calls
// take(hit, touching) for each until take returns false. Tori, algebraic surfaces and tapered
// cylinders work this way, so both answers come from the same arithmetic.
#pragma once

#include <vector>

#include "common/geometry/local_hit.h"

namespace tessera {

// The nearest hit: the search ends at the first one, so the farther ones are never computed.
template <class Visit>
bool nearest_ordered_hit(const Visit& visit, LocalHit& hit) {
  bool found = false;
  visit([&](const LocalHit& first, bool) {
    hit = first;
    found = true;
    return false;
  });
  return found;
}

// Every crossing, for boolean objects. A touching root enters and leaves at once: it is listed
// twice, so that counting crossings still tells inside from outside.
template <class Visit>
std::vector<LocalHit> ordered_crossings(const Visit& visit) {
  std::vector<LocalHit> crossings;
  visit([&](const LocalHit& hit, bool touching) {
    crossings.push_back(hit);
    if (touching) crossings.push_back(hit);
    return true;
  });
  return crossings;
}

}  // namespace tessera
