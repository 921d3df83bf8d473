#include "node/definition_loader.h"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace acomms::node {
namespace fs = std::filesystem;
namespace {

std::string join_lines(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& part : parts) out += (out.empty() ? "" : "\n") + part;
  return out;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) out.push_back(line);
  }
  return out;
}

// An inline name becomes a file under the data dir: it must stay there.
void check_inline_name(const std::string& name) {
  if (name.empty()) throw DefinitionError(DefinitionError::Code::kInvalid, "inline definition needs a name");
  for (char c : name) {
    bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == '/';
    if (!ok) {
      throw DefinitionError(DefinitionError::Code::kInvalid,
                            "inline definition name \"" + name +
                                "\": use letters, digits, '_', '-', '.' and '/' only");
    }
  }
  fs::path path(name);
  for (const auto& part : path) {
    if (part == "..") {
      throw DefinitionError(DefinitionError::Code::kInvalid,
                            "inline definition name \"" + name + "\" must not contain \"..\"");
    }
  }
  if (path.is_absolute()) {
    throw DefinitionError(DefinitionError::Code::kInvalid,
                          "inline definition name \"" + name + "\" must be relative (e.g. \"mission.proto\")");
  }
}

std::optional<std::string> read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

DefinitionLoader::DefinitionLoader(dccl::Codec& codec, queue::QueueManager& queues,
                                   store::GroupCommitWriter& writer, std::string inline_dir)
    : codec_(codec), queues_(queues), writer_(writer), inline_dir_(std::move(inline_dir)) {}

std::vector<RecordedDefinition> DefinitionLoader::read_recorded(store::Database& db) {
  std::vector<RecordedDefinition> out;
  store::Statement statement = db.prepare("SELECT path, include_dirs FROM loaded_definitions ORDER BY id");
  while (statement.step()) out.push_back({statement.column_text(0), split_lines(statement.column_text(1))});
  return out;
}

void DefinitionLoader::load_recorded(dccl::Codec& codec, const std::vector<RecordedDefinition>& recorded) {
  for (const RecordedDefinition& definition : recorded) {
    try {
      const std::map<std::string, std::string> refused_before = codec.refused_types();
      auto types = codec.load(definition.path, definition.include_dirs);
      spdlog::info("dccl: {} (loaded through the API): {} message type{}", definition.path, types.size(),
                   types.size() == 1 ? "" : "s");
      // A type an older acommsd accepted may be refused now (issue 17): the
      // daemon runs on, its stored messages are kept (queue restore).
      for (const auto& [type, why] : codec.refused_types()) {
        if (!refused_before.count(type)) {
          spdlog::warn("dccl: {} (loaded through the API): type {} refused, its stored messages are kept: {}",
                       definition.path, type, why);
        }
      }
    } catch (const dccl::Error& e) {
      spdlog::error("dccl: {} was loaded through the API but no longer loads; messages queued under its "
                    "types will be dropped: {}",
                    definition.path, e.what());
    }
  }
}

std::vector<const dccl::TypeInfo*> DefinitionLoader::load(const v1::LoadDefinitionsRequest& request) {
  std::vector<std::string> include_dirs(request.include_dirs().begin(), request.include_dirs().end());
  std::vector<RecordedDefinition> files;
  for (const std::string& path : request.paths()) {
    check_exists(path, include_dirs);
    files.push_back({path, include_dirs});
  }
  // Inline texts are written first (each checked against what is already
  // there), so that they may import one another.
  // A file this request wrote that then did not load is removed again, so
  // the name stays free for the corrected text.
  std::set<std::string> written;
  std::set<std::string> loaded_paths;
  struct RemoveUnloaded {
    std::set<std::string>& written;
    std::set<std::string>& loaded;
    ~RemoveUnloaded() {
      std::error_code ec;
      for (const std::string& path : written) {
        if (!loaded.count(path)) fs::remove(path, ec);
      }
    }
  } cleanup{written, loaded_paths};
  for (const v1::InlineDefinition& definition : request.inline_()) {
    bool fresh = false;
    files.push_back(write_inline(definition, include_dirs, &fresh));
    if (fresh) written.insert(files.back().path);
  }
  if (files.empty()) {
    throw DefinitionError(DefinitionError::Code::kInvalid, "give at least one path or inline definition");
  }

  std::vector<const dccl::TypeInfo*> types;
  std::vector<std::string> loaded;
  for (const RecordedDefinition& file : files) {
    try {
      auto file_types = codec_.load(file.path, file.include_dirs);
      types.insert(types.end(), file_types.begin(), file_types.end());
    } catch (const dccl::Error& e) {
      std::string before = loaded.empty() ? "" : "\n(loaded before it: " + join_lines(loaded) + ")";
      std::string why = e.what();
      // Syntax errors already begin "file:line:col"; DCCL rule errors name
      // only the type, so say which file.
      std::string name = display_name(file.path);
      if (why.find(name) == std::string::npos) why = name + ": " + why;
      throw DefinitionError(DefinitionError::Code::kInvalid, why + before);
    }
    loaded.push_back(display_name(file.path));
    loaded_paths.insert(file.path);
    queues_.add_types();
    record(file);
  }
  return types;
}

// Inline definitions by the name the client gave, not where they are kept.
std::string DefinitionLoader::display_name(const std::string& path) const {
  std::string prefix = fs::absolute(inline_dir_).string() + "/";
  return path.rfind(prefix, 0) == 0 ? path.substr(prefix.size()) : path;
}

void DefinitionLoader::check_exists(const std::string& path, const std::vector<std::string>& include_dirs) const {
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return;
  std::vector<std::string> searched = include_dirs;
  searched.insert(searched.end(), codec_.include_dirs().begin(), codec_.include_dirs().end());
  if (!fs::path(path).is_absolute()) {
    for (const std::string& dir : searched) {
      if (fs::is_regular_file(fs::path(dir) / path, ec)) return;
    }
  }
  throw DefinitionError(DefinitionError::Code::kNotFound,
                        "no such .proto file: " + path +
                            (fs::path(path).is_absolute() ? "" : " (looked in " + join_lines(searched) + ")"));
}

RecordedDefinition DefinitionLoader::write_inline(const v1::InlineDefinition& definition,
                                                  const std::vector<std::string>& include_dirs, bool* fresh) {
  check_inline_name(definition.name());
  fs::path path = fs::path(inline_dir_) / definition.name();
  if (std::optional<std::string> existing = read_file(path)) {
    if (*existing != definition.text()) {
      throw DefinitionError(DefinitionError::Code::kInvalid,
                            "inline definition " + definition.name() +
                                " was already loaded with other content; types cannot change while acommsd "
                                "runs: give the new version another name");
    }
  } else {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    // Written whole, then renamed: a crash never leaves half a file that
    // would fail the next start-up's reload.
    fs::path partial = path;
    partial += ".partial";
    {
      std::ofstream out(partial, std::ios::binary | std::ios::trunc);
      out << definition.text();
      out.flush();
      if (!out) {
        throw DefinitionError(DefinitionError::Code::kStore, "cannot write " + partial.string());
      }
    }
    fs::rename(partial, path, ec);
    if (ec) throw DefinitionError(DefinitionError::Code::kStore, "cannot write " + path.string() + ": " + ec.message());
    *fresh = true;
  }
  // Absolute, so a file of the same name in the daemon's working directory
  // is never taken instead.
  RecordedDefinition recorded{fs::absolute(path).string(), {inline_dir_}};
  recorded.include_dirs.insert(recorded.include_dirs.end(), include_dirs.begin(), include_dirs.end());
  return recorded;
}

void DefinitionLoader::record(const RecordedDefinition& definition) {
  std::string dirs = join_lines(definition.include_dirs);
  try {
    writer_
        .submit([path = definition.path, dirs](store::Database& db) {
          db.prepare("INSERT OR IGNORE INTO loaded_definitions (path, include_dirs) VALUES (?, ?)")
              .bind(1, std::string_view(path))
              .bind(2, std::string_view(dirs))
              .step();
        })
        .get();
  } catch (const std::exception& e) {
    throw DefinitionError(DefinitionError::Code::kStore,
                          definition.path + " is loaded but could not be recorded for the next start: " + e.what());
  }
}

}  // namespace acomms::node
