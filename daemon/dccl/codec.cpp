#include "dccl/codec.h"

#include <google/protobuf/compiler/importer.h>
#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor_database.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/message.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <set>
#include <unordered_map>

#include "dccl/bitstream.h"
#include "dccl/crypto.h"
#include "dccl/message_codec.h"
#include "dccl/options.h"

namespace acomms::dccl {
namespace gp = google::protobuf;
namespace fs = std::filesystem;

namespace {

constexpr const char* kOptionsFile = "dccl/option_extensions.proto";

// Collects .proto parse and validation errors as "file:line:col: text".
class ErrorList : public gp::compiler::MultiFileErrorCollector {
 public:
  explicit ErrorList(gp::compiler::DiskSourceTree* tree) : tree_(tree) {}

  void AddError(const std::string& filename, int line, int column, const std::string& message) override {
    std::string name = filename;
    std::string disk;
    if (tree_->VirtualFileToDiskFile(filename, &disk)) name = disk;
    if (line < 0) {
      lines.push_back(name + ": " + message);
    } else {
      lines.push_back(name + ":" + std::to_string(line + 1) + ":" + std::to_string(column + 1) + ": " + message);
    }
  }
  void AddWarning(const std::string&, int, int, const std::string&) override {}

  std::vector<std::string> lines;

 private:
  gp::compiler::DiskSourceTree* tree_;
};

std::string join(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) {
    if (!out.empty()) out += '\n';
    out += l;
  }
  return out;
}

double system_clock_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// Reads the DCCL id: one byte `id << 1`, or when its bit 0 is set two bytes
// little-endian of `(id << 1) | 1`.
int read_id(BitReader& in) {
  try {
    uint64_t v = in.read(8);
    if (v & 1) v |= in.read(8) << 8;
    return static_cast<int>(v >> 1);
  } catch (const TruncatedRead&) {
    throw decode_error("message truncated in the DCCL id");
  }
}

void collect_types(const gp::Descriptor* type, std::vector<const gp::Descriptor*>* out) {
  out->push_back(type);
  for (int i = 0; i < type->nested_type_count(); ++i) collect_types(type->nested_type(i), out);
}

}  // namespace

struct Codec::Plan {
  TypeInfo info;
  MessageBody head;
  MessageBody body;
  const gp::Message* prototype = nullptr;
};

struct Codec::Impl {
  Impl() : errors(&tree), source_db(&tree, &generated_db), pool(&source_db, source_db.GetValidationErrorCollector()),
           factory(&pool) {
    source_db.RecordErrorsTo(&errors);
    factory.SetDelegateToGeneratedFactory(false);
  }

  gp::compiler::DiskSourceTree tree;
  ErrorList errors;
  // Files not found on disk (google/protobuf/descriptor.proto) come from
  // the descriptors compiled into libprotobuf.
  gp::DescriptorPoolDatabase generated_db{*gp::DescriptorPool::generated_pool()};
  gp::compiler::SourceTreeDescriptorDatabase source_db;
  gp::DescriptorPool pool;
  gp::DynamicMessageFactory factory;
  std::unique_ptr<OptionReader> options;
  CodecRegistry registry = CodecRegistry::with_builtins();
  std::vector<std::string> include_dirs;

  std::vector<std::unique_ptr<Plan>> plans;
  std::unordered_map<std::string, Plan*> by_name;
  std::unordered_map<const gp::Descriptor*, Plan*> by_descriptor;
  std::unordered_map<int, Plan*> by_id;
  std::map<std::string, std::string> refused;  // type -> reason (TypeRefused)

  bool strict = false;
  std::function<double()> clock = system_clock_seconds;
  std::optional<BodyCipher> cipher;
  std::set<int> exempt_ids;

  bool encrypts(const TypeInfo& info) const {
    return cipher.has_value() && (info.omit_id || exempt_ids.count(info.id) == 0);
  }

  // A virtual path for proto_file: relative to the include directory that
  // holds it, or (for a file elsewhere) its name, with its directory added.
  std::string virtual_path(const std::string& proto_file, Codec* codec) {
    std::error_code ec;
    fs::path p(proto_file);
    if (!fs::is_regular_file(p, ec)) return proto_file;
    fs::path abs = fs::weakly_canonical(fs::absolute(p), ec);
    for (const std::string& dir : include_dirs) {
      fs::path d = fs::weakly_canonical(fs::absolute(dir), ec);
      fs::path rel = abs.lexically_relative(d);
      if (!rel.empty() && *rel.begin() != "..") return rel.generic_string();
    }
    codec->add_include_dir(abs.parent_path().string());
    return abs.filename().string();
  }

  // A plan for type, which comes from `from` (this codec's pool, or a trial
  // pool whose plans are only checked and thrown away), read with `reader`.
  std::unique_ptr<Plan> compile(const gp::Descriptor* type, const MessageOptions& mo, const gp::DescriptorPool& from,
                                OptionReader& reader, std::vector<std::string>* errs) {
    const std::string& name = type->full_name();
    size_t before = errs->size();
    bool version_ok = mo.has_codec_version && mo.codec_version >= 2 && mo.codec_version <= 4;
    if (!mo.has_codec_version) {
      errs->push_back(name + ": (dccl.msg).codec_version is required");
    } else if (!version_ok) {
      errs->push_back(name + ": codec_version " + std::to_string(mo.codec_version) +
                      " is not supported (use 2, 3 or 4)");
    }
    if (!mo.has_max_bytes) errs->push_back(name + ": (dccl.msg).max_bytes is required");
    if (!mo.omit_id && !mo.has_id) errs->push_back(name + ": (dccl.msg).id is required unless omit_id is set");
    if (!mo.omit_id && mo.has_id && (mo.id < 0 || mo.id > 32767)) {
      errs->push_back(name + ": id " + std::to_string(mo.id) + " is out of range 0..32767");
    }
    if (!version_ok) return nullptr;

    auto plan = std::make_unique<Plan>();
    MessageCompiler compiler(&registry, &reader, &from, {mo.codec_version, mo.codec_group});
    compiler.compile_top(type, &plan->head, &plan->body);
    errs->insert(errs->end(), compiler.errors().begin(), compiler.errors().end());
    if (!compiler.refusals().empty()) {
      if (&from == &pool) refused[name] = join(compiler.refusals());
      return nullptr;  // this type only: not an error of its file
    }

    TypeInfo& info = plan->info;
    info.name = name;
    info.descriptor = type;
    info.omit_id = mo.omit_id;
    info.id = mo.omit_id ? -1 : mo.id;
    info.codec_version = mo.codec_version;
    info.max_bytes = mo.max_bytes;
    info.id_bits = mo.omit_id ? 0 : (mo.id < 128 ? 8 : 16);
    info.head = plan->head.size();
    info.body = plan->body.size();
    info.fields = std::move(compiler.fields());
    if (errs->size() != before) return nullptr;
    if (info.max_size_bytes() > mo.max_bytes) {
      errs->push_back(name + ": encoded size can reach " + std::to_string(info.max_size_bytes()) +
                      " bytes, more than max_bytes " + std::to_string(mo.max_bytes));
      return nullptr;
    }
    if (&from == &pool) plan->prototype = factory.GetPrototype(type);
    return plan;
  }

  // Plans for the DCCL messages of `file` not loaded yet, or none and the
  // reasons in errs. Types already loaded are added to *known instead.
  std::vector<std::unique_ptr<Plan>> plan_file(const gp::FileDescriptor* file, const gp::DescriptorPool& from,
                                               OptionReader& reader, std::vector<const TypeInfo*>* known,
                                               std::vector<std::string>* errs) {
    std::vector<const gp::Descriptor*> types;
    for (int i = 0; i < file->message_type_count(); ++i) collect_types(file->message_type(i), &types);
    std::vector<std::unique_ptr<Plan>> fresh;
    std::unordered_map<int, std::string> new_ids;
    for (const gp::Descriptor* type : types) {
      if (auto it = by_name.find(type->full_name()); it != by_name.end()) {
        known->push_back(&it->second->info);
        continue;
      }
      MessageOptions mo = reader.message_options(type);
      if (!mo.present) continue;  // not a DCCL message (may still be embedded)
      std::unique_ptr<Plan> plan = compile(type, mo, from, reader, errs);
      if (!plan) continue;
      if (!plan->info.omit_id) {
        int id = plan->info.id;
        std::string other;
        if (auto it = by_id.find(id); it != by_id.end()) other = it->second->info.name;
        if (auto it = new_ids.find(id); it != new_ids.end()) other = it->second;
        if (!other.empty()) {
          errs->push_back(plan->info.name + ": DCCL id " + std::to_string(id) + " is already used by " + other);
          continue;
        }
        new_ids[id] = plan->info.name;
      }
      fresh.push_back(std::move(plan));
    }
    return fresh;
  }

  // A file already built into this codec's pool (loaded, or imported by a
  // loaded file) stays as it was built: a DescriptorPool cannot replace it.
  // Reports each file of `file` and its imports, as now on disk, that
  // differs from the version built.
  void check_unchanged(const gp::FileDescriptor* file, std::set<std::string>* seen, std::vector<std::string>* errs) {
    if (!seen->insert(file->name()).second) return;
    for (int i = 0; i < file->dependency_count(); ++i) check_unchanged(file->dependency(i), seen, errs);
    // Asks without building: FindFileByName would load the file from disk.
    // (Public, though protobuf marks it for internal use.)
    if (!pool.InternalIsFileLoaded(file->name())) return;
    const gp::FileDescriptor* built = pool.FindFileByName(file->name());
    gp::FileDescriptorProto now;
    gp::FileDescriptorProto then;
    file->CopyTo(&now);
    built->CopyTo(&then);
    if (now.SerializeAsString() == then.SerializeAsString()) return;
    std::string name = file->name();
    std::string disk;
    if (tree.VirtualFileToDiskFile(name, &disk)) name += " (" + disk + ")";
    errs->push_back(name + " has changed since it was loaded, and loaded types cannot be replaced in a "
                    "running process: give the new version another file name, or restart to use it");
  }
};

namespace {

// The public .proto files installed beside the running executable:
// <prefix>/share/acommsd/proto for <prefix>/bin/acommsd (the Debian package,
// `cmake --install --prefix ...`). Empty when there is none, as in a build tree.
std::string installed_proto_dir() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  fs::path dir = exe.parent_path().parent_path() / "share" / "acommsd" / "proto";
  return fs::is_regular_file(dir / kOptionsFile, ec) ? dir.string() : std::string();
}

}  // namespace

Codec::Codec() : impl_(std::make_unique<Impl>()) {
  // An installed binary's own copy comes first: the build-time directory may
  // be a source tree that has since moved on, or not exist on this machine.
  static const std::string installed = installed_proto_dir();
  if (!installed.empty()) add_include_dir(installed);
#ifdef ACOMMS_PROTO_DIR
  add_include_dir(ACOMMS_PROTO_DIR);
#endif
}

Codec::~Codec() = default;

CodecRegistry& Codec::registry() { return impl_->registry; }

void Codec::add_include_dir(const std::string& dir) {
  for (const std::string& d : impl_->include_dirs) {
    if (d == dir) return;
  }
  impl_->include_dirs.push_back(dir);
  impl_->tree.MapPath("", dir);
}

const std::vector<std::string>& Codec::include_dirs() const { return impl_->include_dirs; }

std::vector<const TypeInfo*> Codec::load(const std::string& proto_file,
                                         const std::vector<std::string>& include_dirs) {
  Impl& im = *impl_;
  for (const std::string& d : include_dirs) add_include_dir(d);
  im.errors.lines.clear();

  if (!im.options) {
    if (im.pool.FindFileByName(kOptionsFile) == nullptr) {
      std::string why = im.errors.lines.empty() ? "not found" : join(im.errors.lines);
      throw schema_error(std::string("cannot load ") + kOptionsFile + " (add the directory that holds dccl/ " +
                         "to the include dirs): " + why);
    }
    im.options = std::make_unique<OptionReader>(&im.pool);
  }

  std::string virtual_file = im.virtual_path(proto_file, this);
  auto fail = [&im, &proto_file] {
    if (im.errors.lines.empty()) im.errors.lines.push_back(proto_file + ": cannot load");
    return schema_error(join(im.errors.lines));
  };

  // The file is parsed and checked first in a trial pool of its own. This
  // codec's pool keeps every file it has built, failed DCCL checks or not,
  // and would hand that version back when the corrected file is loaded.
  gp::compiler::SourceTreeDescriptorDatabase trial_db(&im.tree, &im.generated_db);
  trial_db.RecordErrorsTo(&im.errors);
  gp::DescriptorPool trial(&trial_db, trial_db.GetValidationErrorCollector());
  const gp::FileDescriptor* trial_file = trial.FindFileByName(virtual_file);
  if (trial_file == nullptr) throw fail();
  std::vector<std::string> errs;
  std::set<std::string> seen;
  im.check_unchanged(trial_file, &seen, &errs);
  if (!errs.empty()) throw schema_error(join(errs));
  // The reader finds the DCCL options only in a pool that holds them.
  trial.FindFileByName(kOptionsFile);
  OptionReader trial_reader(&trial);
  std::vector<const TypeInfo*> ignored;
  im.plan_file(trial_file, trial, trial_reader, &ignored, &errs);
  if (!errs.empty()) throw schema_error(join(errs));

  const gp::FileDescriptor* file = im.pool.FindFileByName(virtual_file);
  if (file == nullptr) throw fail();
  std::vector<const TypeInfo*> result;
  std::vector<std::unique_ptr<Plan>> fresh = im.plan_file(file, im.pool, *im.options, &result, &errs);
  if (!errs.empty()) throw schema_error(join(errs));

  for (std::unique_ptr<Plan>& plan : fresh) {
    Plan* p = plan.get();
    im.by_name[p->info.name] = p;
    im.by_descriptor[p->info.descriptor] = p;
    if (!p->info.omit_id) im.by_id[p->info.id] = p;
    result.push_back(&p->info);
    im.plans.push_back(std::move(plan));
  }
  return result;
}

const std::map<std::string, std::string>& Codec::refused_types() const { return impl_->refused; }

std::string Codec::refusal(std::string_view full_name) const {
  auto it = impl_->refused.find(std::string(full_name));
  return it == impl_->refused.end() ? std::string() : it->second;
}

const TypeInfo* Codec::find_type(std::string_view full_name) const {
  auto it = impl_->by_name.find(std::string(full_name));
  return it == impl_->by_name.end() ? nullptr : &it->second->info;
}

const TypeInfo* Codec::find_id(int id) const {
  auto it = impl_->by_id.find(id);
  return it == impl_->by_id.end() ? nullptr : &it->second->info;
}

std::vector<const TypeInfo*> Codec::types() const {
  std::vector<const TypeInfo*> out;
  for (const auto& p : impl_->plans) out.push_back(&p->info);
  return out;
}

std::unique_ptr<gp::Message> Codec::new_message(std::string_view full_name) const {
  auto it = impl_->by_name.find(std::string(full_name));
  if (it == impl_->by_name.end()) {
    if (std::string why = refusal(full_name); !why.empty()) {
      throw encode_error("unknown type " + std::string(full_name) + " (refused at load: " + why + ")");
    }
    throw encode_error("DCCL type " + std::string(full_name) + " is not loaded");
  }
  return std::unique_ptr<gp::Message>(it->second->prototype->New());
}

const Codec::Plan& Codec::plan_for(const gp::Message& msg, std::unique_ptr<gp::Message>* copy) const {
  auto it = impl_->by_descriptor.find(msg.GetDescriptor());
  if (it != impl_->by_descriptor.end()) return *it->second;
  // Same type from another pool (e.g. generated code): copy through the wire.
  auto by_name = impl_->by_name.find(msg.GetDescriptor()->full_name());
  if (by_name == impl_->by_name.end()) {
    throw encode_error("DCCL type " + msg.GetDescriptor()->full_name() + " is not loaded");
  }
  copy->reset(by_name->second->prototype->New());
  (*copy)->ParsePartialFromString(msg.SerializePartialAsString());
  return *by_name->second;
}

std::string Codec::encode(const gp::Message& msg) const {
  std::unique_ptr<gp::Message> copy;
  const Plan& plan = plan_for(msg, &copy);
  const gp::Message& m = copy ? *copy : msg;
  const TypeInfo& info = plan.info;

  std::string out;
  out.reserve(info.max_bytes);
  BitWriter w(&out);
  if (!info.omit_id) {
    uint64_t id = static_cast<uint64_t>(info.id);
    if (info.id_bits == 8) {
      w.write(id << 1, 8);
    } else {
      w.write((id << 1) | 1, 16);
    }
  }
  EncodeContext ctx{impl_->strict};
  plan.head.encode(m, w, ctx);
  w.align();
  const size_t head_bytes = w.position() / 8;
  out.resize(head_bytes);
  plan.body.encode(m, w, ctx);
  w.align();
  out.resize(w.position() / 8);
  if (impl_->encrypts(info)) {
    impl_->cipher->apply(std::string_view(out).substr(0, head_bytes), out.data() + head_bytes,
                         out.size() - head_bytes);
  }
  return out;
}

std::unique_ptr<gp::Message> Codec::decode_one(const Plan& plan, std::string_view bytes, size_t* consumed) const {
  std::unique_ptr<gp::Message> msg(plan.prototype->New());
  DecodeContext ctx{&impl_->clock};
  BitReader in(bytes);
  if (!plan.info.omit_id) read_id(in);
  plan.head.decode(in, msg.get(), ctx);
  in.align();
  const uint64_t body_start = in.position();
  const size_t head_bytes = body_start / 8;

  if (impl_->encrypts(plan.info)) {
    // The body length is only known after decoding, so decrypt everything
    // that follows; CTR makes the extra bytes harmless.
    std::string clear(bytes);
    impl_->cipher->apply(bytes.substr(0, head_bytes), clear.data() + head_bytes, clear.size() - head_bytes);
    BitReader body(clear, body_start);
    plan.body.decode(body, msg.get(), ctx);
    body.align();
    if (consumed) *consumed = body.position() / 8;
    return msg;
  }
  plan.body.decode(in, msg.get(), ctx);
  in.align();
  if (consumed) *consumed = in.position() / 8;
  return msg;
}

std::vector<std::unique_ptr<gp::Message>> Codec::decode(std::string_view bytes) const {
  std::vector<std::unique_ptr<gp::Message>> out;
  size_t pos = 0;
  while (pos < bytes.size()) {
    std::string_view rest = bytes.substr(pos);
    int id = id_of(rest);
    auto it = impl_->by_id.find(id);
    if (it == impl_->by_id.end()) throw decode_error("unknown DCCL id " + std::to_string(id));
    size_t used = 0;
    out.push_back(decode_one(*it->second, rest, &used));
    if (used == 0) break;  // cannot happen with an id; guards against looping
    pos += used;
  }
  return out;
}

std::unique_ptr<gp::Message> Codec::decode_as(std::string_view full_name, std::string_view bytes,
                                              size_t* consumed) const {
  auto it = impl_->by_name.find(std::string(full_name));
  if (it == impl_->by_name.end()) throw decode_error("DCCL type " + std::string(full_name) + " is not loaded");
  const Plan& plan = *it->second;
  if (!plan.info.omit_id) {
    int id = id_of(bytes);
    if (id != plan.info.id) {
      throw decode_error("DCCL id " + std::to_string(id) + " is not " + plan.info.name + " (id " +
                         std::to_string(plan.info.id) + ")");
    }
  }
  return decode_one(plan, bytes, consumed);
}

int Codec::id_of(std::string_view bytes) const {
  BitReader in(bytes);
  return read_id(in);
}

void Codec::set_crypto(std::string_view passphrase, std::set<int> exempt_ids) {
  impl_->cipher.emplace(passphrase);
  impl_->exempt_ids = std::move(exempt_ids);
}

void Codec::clear_crypto() {
  impl_->cipher.reset();
  impl_->exempt_ids.clear();
}

void Codec::set_strict(bool strict) { impl_->strict = strict; }
bool Codec::strict() const { return impl_->strict; }

void Codec::set_clock(std::function<double()> clock) {
  impl_->clock = clock ? std::move(clock) : std::function<double()>(system_clock_seconds);
}

}  // namespace acomms::dccl
