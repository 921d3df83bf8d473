#include "dccl/schema_loader.h"

#include <google/protobuf/compiler/importer.h>
#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor_database.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/message.h>

#include <filesystem>
#include <set>
#include <unordered_map>

#include "dccl/error.h"
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

void collect_types(const gp::Descriptor* type, std::vector<const gp::Descriptor*>* out) {
  out->push_back(type);
  for (int i = 0; i < type->nested_type_count(); ++i) collect_types(type->nested_type(i), out);
}

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

struct SchemaLoader::Pools {
  Pools() : errors(&tree), source_db(&tree, &generated_db), pool(&source_db, source_db.GetValidationErrorCollector()),
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

  std::vector<std::unique_ptr<TypePlan>> plans;
  std::unordered_map<std::string, TypePlan*> by_name;
  std::unordered_map<const gp::Descriptor*, TypePlan*> by_descriptor;
  std::unordered_map<int, TypePlan*> by_id;
  std::unordered_map<int, std::string> reserved;  // id -> what it is reserved for
  std::map<std::string, std::string> refused;  // type -> reason (TypeRefused)

  void add_include_dir(const std::string& dir) {
    for (const std::string& d : include_dirs) {
      if (d == dir) return;
    }
    include_dirs.push_back(dir);
    tree.MapPath("", dir);
  }

  // A virtual path for proto_file: relative to the include directory that
  // holds it, or (for a file elsewhere) its name, with its directory added.
  std::string virtual_path(const std::string& proto_file) {
    std::error_code ec;
    fs::path p(proto_file);
    if (!fs::is_regular_file(p, ec)) return proto_file;
    fs::path abs = fs::weakly_canonical(fs::absolute(p), ec);
    for (const std::string& dir : include_dirs) {
      fs::path d = fs::weakly_canonical(fs::absolute(dir), ec);
      fs::path rel = abs.lexically_relative(d);
      if (!rel.empty() && *rel.begin() != "..") return rel.generic_string();
    }
    add_include_dir(abs.parent_path().string());
    return abs.filename().string();
  }

  // The DCCL options are read through this pool's copy of
  // dccl/option_extensions.proto, built on the first load.
  void require_options() {
    if (options) return;
    if (pool.FindFileByName(kOptionsFile) == nullptr) {
      std::string why = errors.lines.empty() ? "not found" : join(errors.lines);
      throw schema_error(std::string("cannot load ") + kOptionsFile + " (add the directory that holds dccl/ " +
                         "to the include dirs): " + why);
    }
    options = std::make_unique<OptionReader>(&pool);
  }

  // The message-level DCCL rules of `type` (codec_version, max_bytes, id),
  // then a plan for it compiled from `from` (this loader's pool, or a trial
  // pool whose plans are only checked and thrown away), read with `reader`.
  // Null, with the reasons in errs, when a rule is broken.
  std::unique_ptr<TypePlan> compile(const gp::Descriptor* type, const MessageOptions& mo,
                                    const gp::DescriptorPool& from, OptionReader& reader,
                                    std::vector<std::string>* errs) {
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

    auto plan = std::make_unique<TypePlan>();
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
  std::vector<std::unique_ptr<TypePlan>> plan_file(const gp::FileDescriptor* file, const gp::DescriptorPool& from,
                                                   OptionReader& reader, std::vector<const TypeInfo*>* known,
                                                   std::vector<std::string>* errs) {
    std::vector<const gp::Descriptor*> types;
    for (int i = 0; i < file->message_type_count(); ++i) collect_types(file->message_type(i), &types);
    std::vector<std::unique_ptr<TypePlan>> fresh;
    std::unordered_map<int, std::string> new_ids;
    for (const gp::Descriptor* type : types) {
      if (auto it = by_name.find(type->full_name()); it != by_name.end()) {
        known->push_back(&it->second->info);
        continue;
      }
      MessageOptions mo = reader.message_options(type);
      if (!mo.present) continue;  // not a DCCL message (may still be embedded)
      std::unique_ptr<TypePlan> plan = compile(type, mo, from, reader, errs);
      if (!plan) continue;
      if (!plan->info.omit_id) {
        int id = plan->info.id;
        std::string other;
        if (auto it = by_id.find(id); it != by_id.end()) other = it->second->info.name;
        if (auto it = new_ids.find(id); it != new_ids.end()) other = it->second;
        if (auto it = reserved.find(id); it != reserved.end()) {
          errs->push_back(plan->info.name + ": DCCL id " + std::to_string(id) + " is reserved for " + it->second +
                          ": give the type another id");
          continue;
        }
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

  // A file already built into this loader's pool (loaded, or imported by a
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

  // Parses and checks virtual_file in a trial pool of its own, and throws
  // every problem found. This loader's pool keeps every file it has built,
  // failed DCCL checks or not, and would hand that version back when the
  // corrected file is loaded.
  void trial_load(const std::string& virtual_file, const std::string& proto_file) {
    gp::compiler::SourceTreeDescriptorDatabase trial_db(&tree, &generated_db);
    trial_db.RecordErrorsTo(&errors);
    gp::DescriptorPool trial(&trial_db, trial_db.GetValidationErrorCollector());
    const gp::FileDescriptor* trial_file = trial.FindFileByName(virtual_file);
    if (trial_file == nullptr) throw cannot_load(proto_file);
    std::vector<std::string> errs;
    std::set<std::string> seen;
    check_unchanged(trial_file, &seen, &errs);
    if (!errs.empty()) throw schema_error(join(errs));
    // The reader finds the DCCL options only in a pool that holds them.
    trial.FindFileByName(kOptionsFile);
    OptionReader trial_reader(&trial);
    std::vector<const TypeInfo*> ignored;
    plan_file(trial_file, trial, trial_reader, &ignored, &errs);
    if (!errs.empty()) throw schema_error(join(errs));
  }

  // The .proto errors collected, or that proto_file cannot be loaded.
  Error cannot_load(const std::string& proto_file) {
    if (errors.lines.empty()) errors.lines.push_back(proto_file + ": cannot load");
    return schema_error(join(errors.lines));
  }

  void add(std::unique_ptr<TypePlan> plan) {
    TypePlan* p = plan.get();
    by_name[p->info.name] = p;
    by_descriptor[p->info.descriptor] = p;
    if (!p->info.omit_id) by_id[p->info.id] = p;
    plans.push_back(std::move(plan));
  }
};

SchemaLoader::SchemaLoader() : pools_(std::make_unique<Pools>()) {
  // An installed binary's own copy comes first: the build-time directory may
  // be a source tree that has since moved on, or not exist on this machine.
  static const std::string installed = installed_proto_dir();
  if (!installed.empty()) add_include_dir(installed);
#ifdef ACOMMS_PROTO_DIR
  add_include_dir(ACOMMS_PROTO_DIR);
#endif
}

SchemaLoader::~SchemaLoader() = default;

CodecRegistry& SchemaLoader::registry() { return pools_->registry; }

void SchemaLoader::add_include_dir(const std::string& dir) { pools_->add_include_dir(dir); }

const std::vector<std::string>& SchemaLoader::include_dirs() const { return pools_->include_dirs; }

std::vector<const TypeInfo*> SchemaLoader::load(const std::string& proto_file,
                                                const std::vector<std::string>& include_dirs) {
  Pools& p = *pools_;
  for (const std::string& d : include_dirs) add_include_dir(d);
  p.errors.lines.clear();
  p.require_options();

  std::string virtual_file = p.virtual_path(proto_file);
  p.trial_load(virtual_file, proto_file);

  const gp::FileDescriptor* file = p.pool.FindFileByName(virtual_file);
  if (file == nullptr) throw p.cannot_load(proto_file);
  std::vector<const TypeInfo*> result;
  std::vector<std::string> errs;
  std::vector<std::unique_ptr<TypePlan>> fresh = p.plan_file(file, p.pool, *p.options, &result, &errs);
  if (!errs.empty()) throw schema_error(join(errs));

  for (std::unique_ptr<TypePlan>& plan : fresh) {
    result.push_back(&plan->info);
    p.add(std::move(plan));
  }
  return result;
}

const TypePlan* SchemaLoader::find(std::string_view full_name) const {
  auto it = pools_->by_name.find(std::string(full_name));
  return it == pools_->by_name.end() ? nullptr : it->second;
}

const TypePlan* SchemaLoader::find(const gp::Descriptor* type) const {
  auto it = pools_->by_descriptor.find(type);
  return it == pools_->by_descriptor.end() ? nullptr : it->second;
}

const TypePlan* SchemaLoader::find_id(int id) const {
  auto it = pools_->by_id.find(id);
  return it == pools_->by_id.end() ? nullptr : it->second;
}

void SchemaLoader::reserve_id(int id, const std::string& owner) { pools_->reserved[id] = owner; }

const std::map<std::string, std::string>& SchemaLoader::refused_types() const { return pools_->refused; }

std::vector<const TypeInfo*> SchemaLoader::types() const {
  std::vector<const TypeInfo*> out;
  for (const auto& plan : pools_->plans) out.push_back(&plan->info);
  return out;
}

}  // namespace acomms::dccl
