// The VRML97 parser (ISO/IEC 14772-1 §5 and §4.8-4.9): nodes with typed fields, DEF/USE,
// PROTO instances expanded with their default and given field values, EXTERNPROTO, ROUTE.
// Non-visual nodes and ROUTEs are accepted and counted, so that the loader can list them in one
// warning.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "common/loaders/load_budget.h"
#include "common/loaders/vrml_lexer.h"
#include "common/loaders/vrml_nodes.h"

namespace tessera::vrml {

struct ParsedWorld {
  std::vector<NodePtr> roots;
  std::map<std::string, int> ignored;      // non-visual node types and ROUTE, with counts
  std::map<std::string, int> unsupported;  // visual node types that are not rendered
  std::vector<std::string> warnings;       // located, one per EXTERNPROTO
};

// Throws SceneError at the offending token: "file:line:column: what was expected". Nodes (parsed
// and made by PROTO expansion), PROTO instances, nesting and the memory of the nodes count
// against `meter`'s budget.
ParsedWorld parse_vrml(const LexedFile& file, LoadMeter& meter);
// With its own meter of `budget`.
ParsedWorld parse_vrml(const LexedFile& file, const LoadBudget& budget = {});

}  // namespace tessera::vrml
