// The VRML97 parser (ISO/IEC 14772-1 §5 and §4.8-4.9): nodes with typed fields, DEF/USE,
// PROTO instances expanded with their default and given field values, EXTERNPROTO, ROUTE.
// Non-visual nodes and ROUTEs are accepted and counted, so that the loader can list them in one
// warning.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/loaders/load_budget.h"
#include "common/loaders/vrml_lexer.h"
#include "common/loaders/vrml_nodes.h"

namespace tessera::vrml {

// A PROTO's interface field: its type and default value (none for events and EXTERNPROTOs).
struct ProtoField {
  FieldType type = FieldType::SFFloat;
  std::optional<FieldValue> value;
};

struct Proto {
  std::string name;
  std::map<std::string, ProtoField> interface;
  std::vector<NodePtr> body;           // the first node is what an instance renders as
  bool external = false;               // an EXTERNPROTO none of whose urls could be read: not drawn
  const NodeSpec* built_in = nullptr;  // an EXTERNPROTO of a urn:web3d:vrml97:node: name
  std::uint64_t nested_instances = 0;  // PROTO instances its body holds, each made anew
};

struct ParsedWorld {
  std::vector<NodePtr> roots;
  std::map<std::string, int> ignored;      // non-visual node types and ROUTE, with counts
  std::map<std::string, int> unsupported;  // visual node types that are not rendered
  std::vector<std::string> warnings;       // located: what lenient loading left out
  std::map<std::string, Proto> protos;     // the file's PROTOs, for EXTERNPROTOs elsewhere
  std::string first_proto;                 // what an EXTERNPROTO url without '#Name' means
};

// The files EXTERNPROTO urls name, read and parsed like Inlined files (the loader's cache).
class ProtoFiles {
 public:
  virtual ~ProtoFiles() = default;
  // The world of `url` (without its '#Name'), relative to the file at `from_file`; null when
  // it cannot be read, with `why` saying why ("'x.wrl' not found").
  virtual const ParsedWorld* proto_file(const std::string& from_file, const std::string& url,
                                        const SourceLocation& at, std::string& why) = 0;
};

// A part of a world left out (a missing texture, a node or field outside VRML97, a url
// scheme the loader does not read): a located warning in `warnings`, at most
// `budget.max_warnings` of them, or under `budget.strict` a SceneError.
void leave_out(const LoadBudget& budget, std::vector<std::string>& warnings,
               const SourceLocation& where, const std::string& message);

// The file path a url names: the url itself, or what follows "file:" ("file:///a/b" is
// "/a/b"); nullopt for another scheme ("http://...", "urn:..."), which the loader does not
// read. A scheme has two or more characters before ':' (one is a Windows drive letter).
std::optional<std::string> local_path_of_url(const std::string& url);

// Throws SceneError at the offending token: "file:line:column: what was expected". Nodes (parsed
// and made by PROTO expansion), PROTO instances, nesting and the memory of the nodes count
// against `meter`'s budget. EXTERNPROTO urls naming files are read through `files` (none:
// their instances are left out).
ParsedWorld parse_vrml(const LexedFile& file, LoadMeter& meter, ProtoFiles* files = nullptr);
// With its own meter of `budget`.
ParsedWorld parse_vrml(const LexedFile& file, const LoadBudget& budget = {});

}  // namespace tessera::vrml
