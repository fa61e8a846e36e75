#include "common/loaders/vrml_parser.h"

#include <cctype>
#include <optional>
#include <string>

#include "common/loaders/lexical.h"

namespace tessera::vrml {
namespace {

bool is_number_start(const Token& t) {
  if (t.kind != Token::Kind::Word || t.text.empty()) return false;
  const char c = t.text[0];
  return (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.';
}

// Approximate memory of parsed values and nodes (LoadBudget::max_bytes_produced): the
// containers' own sizes, a map entry's overhead, and what lies on the heap.
constexpr std::uint64_t kHeapString = 16;                // beyond std::string's own buffer
constexpr std::uint64_t kNodeBytes = sizeof(Node) + 32;  // and make_shared's control block

std::uint64_t field_bytes(const FieldValue& v) {
  std::uint64_t bytes = sizeof(FieldValue) + sizeof(std::string) + 48 +
                        v.numbers.size() * sizeof(double) + v.nodes.size() * sizeof(NodePtr);
  for (const std::string& text : v.strings) bytes += sizeof(std::string) + text.size();
  return bytes;
}

constexpr std::string_view kBuiltInUrn = "urn:web3d:vrml97:node:";

class Parser {
 public:
  Parser(const LexedFile& file, LoadMeter& meter, ParsedWorld& world, ProtoFiles* files)
      : file_(file), meter_(meter), world_(world), files_(files) {}

  void run() {
    while (!at_end())
      if (NodePtr node = statement()) world_.roots.push_back(std::move(node));
  }

 private:
  // ---- Tokens
  bool at_end() const { return next_ == file_.tokens.size(); }
  const Token* peek(std::size_t ahead = 0) const {
    return next_ + ahead < file_.tokens.size() ? &file_.tokens[next_ + ahead] : nullptr;
  }
  bool peek_is(const char* text, std::size_t ahead = 0) const {
    const Token* t = peek(ahead);
    return t && t->kind != Token::Kind::String && t->text == text;
  }
  SourceLocation location(const Token& t) const { return {file_.path, t.line, t.column}; }
  [[noreturn]] void fail(const Token& at, const std::string& message) const {
    throw SceneError(location(at), message);
  }
  void leave_out(const Token& at, const std::string& message) {
    vrml::leave_out(meter_.budget(), world_.warnings, location(at), message);
  }
  const Token& take(const std::string& what) {
    if (at_end())
      throw SceneError({file_.path, file_.end_line, file_.end_column},
                       "unexpected end of file: expected " + what);
    return file_.tokens[next_++];
  }
  const Token& take_word(const std::string& what) {
    const Token& t = take(what);
    if (t.kind != Token::Kind::Word) fail(t, "expected " + what + ", found " + in_quotes(t.text));
    return t;
  }
  void expect(const char* punct, const std::string& what) {
    const Token& t = take("'" + std::string(punct) + "' " + what);
    if (t.kind != Token::Kind::Punct || t.text != punct)
      fail(t, "expected '" + std::string(punct) + "' " + what + ", found " + in_quotes(t.text));
  }
  SourceLocation last_location() const { return location(file_.tokens[next_ - 1]); }
  void count_node() {
    const auto at = [this] { return last_location(); };
    meter_.add(LoadLimit::Nodes, 1, at);
    meter_.add(LoadLimit::BytesProduced, kNodeBytes + file_.path.size() + kHeapString, at);
  }
  void count_bytes(std::uint64_t bytes) {
    meter_.add(LoadLimit::BytesProduced, bytes, [this] { return last_location(); });
  }

  // ---- Statements (§5.7): a node, PROTO, EXTERNPROTO or ROUTE. Null for what is not drawn.
  NodePtr statement() {
    if (peek_is("PROTO")) {
      proto_declaration();
    } else if (peek_is("EXTERNPROTO")) {
      extern_proto_declaration();
    } else if (peek_is("ROUTE")) {
      route();
    } else {
      return node_statement();
    }
    return nullptr;
  }

  void route() {
    take("ROUTE");
    take_word("a node.eventOut after 'ROUTE'");
    const Token& to = take_word("'TO' in the ROUTE");
    if (to.text != "TO") fail(to, "expected 'TO' in the ROUTE, found " + in_quotes(to.text));
    take_word("a node.eventIn after 'TO'");
    ++world_.ignored["ROUTE"];
  }

  NodePtr node_statement() {
    const Token& first = take_word("a node");
    if (first.text == "USE") {
      const Token& name = take_word("a node name after 'USE'");
      const auto found = defs_.find(name.text);
      if (found == defs_.end()) fail(name, "node " + in_quotes(name.text) + " is not DEFined");
      return found->second;
    }
    if (first.text == "DEF") {
      const Token& name = take_word("a node name after 'DEF'");
      const Token& type = take_word("a node type after 'DEF " + name.text + "'");
      // A Script may USE the node it is DEFined as (§4.6.2 allows it); a Script is not drawn,
      // so the name stands for no node until its body is read.
      if (const NodeSpec* spec = find_node_spec(type.text);
          spec && spec->role != NodeRole::Rendered)
        defs_[name.text] = nullptr;
      NodePtr node = node_body(type);
      defs_[name.text] = node;
      return node;
    }
    return node_body(first);
  }

  NodePtr node_body(const Token& type) {
    if (++depth_ > meter_.budget().max_node_nesting)
      meter_.fail(LoadLimit::NodeNesting, location(type),
                  "nodes nest deeper than " + std::to_string(meter_.budget().max_node_nesting));
    count_node();
    NodePtr out;
    if (const auto declared = protos_.find(type.text);
        declared != protos_.end() && declared->second.built_in) {
      out = built_in_node(*declared->second.built_in, type);
    } else if (declared != protos_.end()) {
      out = proto_instance(declared->second, type);
    } else if (const NodeSpec* spec = find_node_spec(type.text)) {
      if (spec->role == NodeRole::Rendered) {
        out = built_in_node(*spec, type);
      } else {
        expect("{", "after " + in_quotes(type.text));
        skip_fields();
        ++(spec->role == NodeRole::NonVisual ? world_.ignored : world_.unsupported)[type.text];
      }
    } else {
      leave_out(type, "unknown node type " + in_quotes(type.text));
      expect("{", "after " + in_quotes(type.text));
      skip_fields();
    }
    --depth_;
    return out;
  }

  NodePtr built_in_node(const NodeSpec& spec, const Token& type) {
    auto node = std::make_shared<Node>();
    node->type = spec.type;
    node->where = location(type);
    expect("{", "after " + in_quotes(type.text));
    while (!peek_is("}")) {
      if (peek_is("ROUTE") || peek_is("PROTO") || peek_is("EXTERNPROTO")) {
        statement();
        continue;
      }
      const Token& name = take_word("a field of " + type.text + " or '}'");
      const FieldSpec* field = spec.field(name.text);
      if (peek_is("IS")) {
        const std::optional<FieldType> link = is_link(name);
        // eventIns and eventOuts (set_translation IS ...) carry no value: nothing to link.
        if (field && link && *link != field->type)
          fail(name, in_quotes(name.text) + " of " + type.text + " has another type than the " +
                         "PROTO field it IS");
        if (field) node->is_links[name.text] = file_.tokens[next_ - 1].text;
        continue;
      }
      if (!field) {
        leave_out(name, "unknown field " + in_quotes(name.text) + " of " + type.text);
        skip_value(name);
        continue;
      }
      FieldValue& value = node->fields[name.text];
      value = field_value(field->type, name.text + " of " + type.text);
      count_bytes(field_bytes(value));
    }
    take("}");
    return node;
  }

  // `IS name` inside a PROTO body: the interface field's type, or nullopt outside of one.
  std::optional<FieldType> is_link(const Token& field) {
    take("IS");
    const Token& name = take_word("a PROTO field after 'IS'");
    if (!proto_) fail(field, "'IS' outside of a PROTO body");
    const auto found = proto_->interface.find(name.text);
    if (found == proto_->interface.end())
      fail(name, in_quotes(name.text) + " is not a field of PROTO " + in_quotes(proto_->name));
    return found->second.type;
  }

  // ---- Field values (§5.8): one element, or for MF types a bracketed list of them.
  FieldValue field_value(FieldType type, const std::string& of) {
    FieldValue out;
    out.type = type;
    if (const Token* t = peek()) out.where = location(*t);
    if (is_multiple(type) && peek_is("[")) {
      take("[");
      while (!peek_is("]")) element(out, of);
      take("]");
    } else {
      element(out, of);
    }
    return out;
  }

  void element(FieldValue& out, const std::string& of) {
    using enum FieldType;
    switch (out.type) {
      case SFBool:
      case MFBool: {
        const Token& t = take("TRUE or FALSE for " + of);
        if (t.text != "TRUE" && t.text != "FALSE")
          fail(t, "expected TRUE or FALSE for " + of + ", found " + in_quotes(t.text));
        out.numbers.push_back(t.text == "TRUE" ? 1 : 0);
        return;
      }
      case SFInt32:
      case MFInt32:
        out.numbers.push_back(integer(of));
        return;
      case SFString:
      case MFString: {
        const Token& t = take("a string for " + of);
        if (t.kind != Token::Kind::String)
          fail(t, "expected a string in quotes for " + of + ", found " + in_quotes(t.text));
        out.strings.push_back(t.text);
        return;
      }
      case SFNode:
      case MFNode:
        if (peek_is("NULL")) {
          take("NULL");
        } else if (NodePtr node = node_statement(); node || out.type == MFNode) {
          // A node that is not drawn stays in an MFNode as null, so that the others keep
          // their indices (Switch's whichChoice counts every child, §6.46).
          out.nodes.push_back(std::move(node));
        }
        return;
      default:
        for (int k = components(out.type); k > 0; --k) out.numbers.push_back(number(of));
    }
  }

  double number(const std::string& of) {
    const Token& t = take("a number for " + of);
    const DecimalResult r = t.kind == Token::Kind::Word ? parse_decimal(t.text) : DecimalResult{};
    if (r.status == DecimalStatus::OutOfRange) fail(t, "number out of range for " + of);
    if (r.status != DecimalStatus::Ok)
      fail(t, "expected a number for " + of + ", found " + in_quotes(t.text));
    return r.value;
  }

  double integer(const std::string& of) {
    const Token& t = take("an integer for " + of);
    long long value = 0;
    bool ok = false;
    if (t.kind == Token::Kind::Word && (t.text.starts_with("0x") || t.text.starts_with("0X"))) {
      ok = t.text.size() > 2 && t.text.size() <= 10;  // §5.3.5: hexadecimal, 32 bits
      for (std::size_t i = 2; ok && i < t.text.size(); ++i)
        ok = std::isxdigit(static_cast<unsigned char>(t.text[i])) != 0;
      if (ok) value = std::stoll(t.text.substr(2), nullptr, 16);
    } else if (t.kind == Token::Kind::Word) {
      const IntegerResult r = parse_integer(t.text);
      ok = r.status == DecimalStatus::Ok && r.value >= -2147483648LL && r.value <= 2147483647LL;
      value = r.value;
    }
    if (!ok) fail(t, "expected a 32-bit integer for " + of + ", found " + in_quotes(t.text));
    return static_cast<double>(value);
  }

  // ---- Nodes that are not drawn: their fields are skipped by shape (atoms, lists, nodes), so
  // that DEFs inside them still count. Script's own field declarations are read by type.
  void skip_fields() {
    while (!peek_is("}")) {
      const Token& name = take_word("a field or '}'");
      if (name.text == "field" || name.text == "exposedField" || name.text == "eventIn" ||
          name.text == "eventOut") {
        const bool has_value = name.text == "field" || name.text == "exposedField";
        const FieldType type = field_type();
        take_word("a field name");
        if (peek_is("IS")) {
          is_link(name);
        } else if (has_value) {
          field_value(type, "a Script field");
        }
        continue;
      }
      skip_value(name);
    }
    take("}");
  }

  void skip_value(const Token& field) {
    if (peek_is("IS")) {
      is_link(field);
    } else if (peek_is("[")) {
      take("[");
      while (!peek_is("]")) skip_atom_or_node();
      take("]");
    } else if (!skip_atoms()) {
      skip_atom_or_node();
    }
  }

  // Consumes numbers, strings, TRUE and FALSE; false when there was none.
  bool skip_atoms() {
    bool any = false;
    for (const Token* t = peek();
         t && (t->kind == Token::Kind::String || is_number_start(*t) || t->text == "TRUE" ||
               t->text == "FALSE" || t->text == "NULL");
         t = peek()) {
      ++next_;
      any = true;
    }
    return any;
  }

  void skip_atom_or_node() {
    if (skip_atoms()) return;
    if (peek_is("[") || peek_is("{") || peek_is("}"))
      fail(*peek(), "unexpected " + in_quotes(peek()->text));
    node_statement();
  }

  FieldType field_type() {
    const Token& t = take_word("a field type");
    FieldType type;
    if (!parse_field_type(t.text, type))
      fail(t, "expected a field type (SFBool ... MFNode), found " + in_quotes(t.text));
    return type;
  }

  // ---- PROTO (§4.8)
  void proto_interface(Proto& proto, bool with_values) {
    expect("[", "to open the interface of " + in_quotes(proto.name));
    while (!peek_is("]")) {
      const Token& kind = take_word("field, exposedField, eventIn, eventOut or ']'");
      const bool is_field = kind.text == "field" || kind.text == "exposedField";
      if (!is_field && kind.text != "eventIn" && kind.text != "eventOut")
        fail(kind,
             "expected field, exposedField, eventIn or eventOut, found " + in_quotes(kind.text));
      ProtoField field;
      field.type = field_type();
      const Token& name = take_word("a field name");
      if (is_field && with_values)
        field.value =
            field_value(field.type, in_quotes(name.text) + " of PROTO " + in_quotes(proto.name));
      proto.interface[name.text] = std::move(field);
    }
    take("]");
  }

  void proto_declaration() {
    take("PROTO");
    Proto proto;
    proto.name = take_word("a PROTO name").text;
    proto_interface(proto, true);
    expect("{", "to open the body of PROTO " + in_quotes(proto.name));
    // The body has its own DEF names (§4.8.3); it sees the PROTOs declared before it.
    std::map<std::string, NodePtr> outer_defs;
    outer_defs.swap(defs_);
    Proto* outer_proto = proto_;
    proto_ = &proto;
    const std::uint64_t instances_before = meter_.total(LoadLimit::ProtoInstances);
    while (!peek_is("}"))
      if (NodePtr node = statement()) proto.body.push_back(std::move(node));
    take("}");
    proto.nested_instances = meter_.total(LoadLimit::ProtoInstances) - instances_before;
    proto_ = outer_proto;
    defs_.swap(outer_defs);
    if (world_.first_proto.empty()) world_.first_proto = proto.name;
    world_.protos[proto.name] = proto;
    protos_[proto.name] = std::move(proto);
  }

  void extern_proto_declaration() {
    const Token& keyword = take("EXTERNPROTO");
    Proto proto;
    proto.name = take_word("an EXTERNPROTO name").text;
    proto.external = true;
    proto_interface(proto, false);
    const FieldValue urls =
        field_value(FieldType::MFString, "the url of EXTERNPROTO " + in_quotes(proto.name));
    std::string why;  // of the last url that could not be read
    for (const std::string& url : urls.strings) {
      if (const std::optional<Proto> found = external_definition(url, urls.where, why)) {
        const std::string name = proto.name;
        proto = *found;
        proto.name = name;
        protos_[proto.name] = std::move(proto);
        return;
      }
    }
    leave_out(keyword, "EXTERNPROTO " + in_quotes(proto.name) + ": " +
                           (why.empty() ? "it has no url" : why) + ": its instances are left out");
    protos_[proto.name] = std::move(proto);
  }

  // What one EXTERNPROTO url names (§4.9.2-4.9.3): a built-in node by its urn, a PROTO of this
  // file ("#Name"), or a PROTO of another file (the one named after '#', or its first);
  // nullopt with `why` when it names none of these.
  std::optional<Proto> external_definition(const std::string& url, const SourceLocation& at,
                                           std::string& why) {
    if (url.starts_with(kBuiltInUrn)) {
      const std::string name = url.substr(kBuiltInUrn.size());
      const NodeSpec* spec = find_node_spec(name);
      if (spec && spec->role == NodeRole::Rendered) {
        Proto alias;
        alias.built_in = spec;
        return alias;
      }
      why = in_quotes(url) + " is not a node this loader draws";
      return std::nullopt;
    }
    const std::optional<std::string> local = local_path_of_url(url);
    if (!local) {
      why = "the url scheme of " + in_quotes(url) + " is not read (the loader fetches nothing)";
      return std::nullopt;
    }
    const std::size_t hash = local->find('#');
    const std::string path = local->substr(0, hash);
    const std::string name = hash == std::string::npos ? "" : local->substr(hash + 1);
    const std::map<std::string, Proto>* protos = &protos_;
    std::string first;
    if (!path.empty()) {
      const ParsedWorld* world = files_ ? files_->proto_file(file_.path, path, at, why) : nullptr;
      if (!world) {
        if (!files_) why = in_quotes(path) + " is not read here";
        return std::nullopt;
      }
      protos = &world->protos;
      first = world->first_proto;
    }
    const auto found = protos->find(name.empty() ? first : name);
    if (found == protos->end()) {
      why = in_quotes(url) + " names no PROTO";
      return std::nullopt;
    }
    return found->second;
  }

  NodePtr proto_instance(Proto& proto, const Token& type) {
    // The body's own instances were expanded when it was parsed; each instance copies them.
    meter_.add(LoadLimit::ProtoInstances, 1 + proto.nested_instances,
               [&] { return location(type); });
    expect("{", "after " + in_quotes(type.text));
    std::map<std::string, FieldValue> values;
    std::map<std::string, std::string> relinks;  // instance field -> enclosing PROTO's field
    while (!peek_is("}")) {
      const Token& name = take_word("a field of PROTO " + in_quotes(proto.name) + " or '}'");
      const auto field = proto.interface.find(name.text);
      if (field == proto.interface.end()) {
        leave_out(name,
                  "unknown field " + in_quotes(name.text) + " of PROTO " + in_quotes(proto.name));
        skip_value(name);
        continue;
      }
      if (peek_is("IS")) {
        is_link(name);
        relinks[name.text] = file_.tokens[next_ - 1].text;
      } else {
        values[name.text] = field_value(
            field->second.type, in_quotes(name.text) + " of PROTO " + in_quotes(proto.name));
      }
    }
    take("}");
    if (proto.external || proto.body.empty()) return nullptr;
    for (const auto& [name, field] : proto.interface)
      if (field.value && !values.count(name)) values[name] = *field.value;
    std::map<const Node*, NodePtr> copies;
    return instantiate(proto.body.front(), values, relinks, copies);
  }

  // A copy of a PROTO body node with every IS field given its value; fields the instance
  // itself links to an enclosing PROTO's field stay links (to that field). Sharing by USE
  // inside the body is kept.
  NodePtr instantiate(const NodePtr& node, const std::map<std::string, FieldValue>& values,
                      const std::map<std::string, std::string>& relinks,
                      std::map<const Node*, NodePtr>& copies) {
    if (!node) return nullptr;  // a node that is not drawn
    if (const auto done = copies.find(node.get()); done != copies.end()) return done->second;
    count_node();
    for (const auto& [name, field] : node->fields) count_bytes(field_bytes(field));
    auto copy = std::make_shared<Node>(*node);
    copy->is_links.clear();
    for (auto& [name, field] : copy->fields)
      for (NodePtr& child : field.nodes) child = instantiate(child, values, relinks, copies);
    for (const auto& [name, link] : node->is_links) {
      if (const auto relinked = relinks.find(link); relinked != relinks.end()) {
        copy->is_links[name] = relinked->second;
      } else if (const auto given = values.find(link); given != values.end()) {
        copy->fields[name] = given->second;
      }
    }
    copies[node.get()] = copy;
    return copy;
  }

  const LexedFile& file_;
  LoadMeter& meter_;
  ParsedWorld& world_;
  ProtoFiles* files_;
  std::size_t next_ = 0;
  std::uint64_t depth_ = 0;
  std::map<std::string, NodePtr> defs_;
  std::map<std::string, Proto> protos_;
  Proto* proto_ = nullptr;  // the PROTO whose body is being parsed
};

}  // namespace

void leave_out(const LoadBudget& budget, std::vector<std::string>& warnings,
               const SourceLocation& where, const std::string& message) {
  if (budget.strict) throw SceneError(where, message);
  if (warnings.size() < budget.max_warnings) warnings.push_back(where.to_string() + ": " + message);
}

std::optional<std::string> local_path_of_url(const std::string& url) {
  std::size_t colon = url.find(':');
  const std::size_t end_of_scheme = url.find_first_of("/#?");
  if (colon == std::string::npos || colon < 2 || colon > end_of_scheme) return url;
  for (std::size_t i = 0; i < colon; ++i)
    if (!std::isalnum(static_cast<unsigned char>(url[i])) && url[i] != '+' && url[i] != '-' &&
        url[i] != '.')
      return url;
  if (to_lower(url.substr(0, colon)) != "file") return std::nullopt;
  std::string path = url.substr(colon + 1);
  if (path.starts_with("//")) {  // file://host/path: only the local host, written empty
    const std::size_t slash = path.find('/', 2);
    const std::string host = path.substr(2, slash == std::string::npos ? slash : slash - 2);
    if (!host.empty() && host != "localhost") return std::nullopt;
    path = slash == std::string::npos ? "" : path.substr(slash);
  }
  return path;
}

ParsedWorld parse_vrml(const LexedFile& file, LoadMeter& meter, ProtoFiles* files) {
  ParsedWorld world;
  Parser(file, meter, world, files).run();
  return world;
}

ParsedWorld parse_vrml(const LexedFile& file, const LoadBudget& budget) {
  LoadMeter meter(budget);
  return parse_vrml(file, meter);
}

}  // namespace tessera::vrml
