#pragma once
// LoadDefinitions' work: DCCL definitions added while the daemon runs
// (service/definitions.h is the face the API sees).
//
// A loaded file is recorded in the store and loaded again at start-up, after
// the config's files: a message queued under a type loaded this way must
// still find its type after a crash. Definitions sent inline are written
// under <data dir>/definitions/, so they survive the same way.
//
// Types cannot change while the daemon runs (the descriptor pool only
// grows, and queued messages were encoded with the old layout): loading a
// different text under a name already used is refused.
//
// Not thread-safe: load() runs on the core thread (see service/definitions.h);
// read_recorded and load_recorded only at start-up.

#include <memory>
#include <string>
#include <vector>

#include "acomms/v1/acomms.pb.h"
#include "dccl/codec.h"
#include "queue/queue_manager.h"
#include "service/definitions.h"
#include "store/group_commit_writer.h"
#include "store/sqlite.h"

namespace acomms::node {

using service::DefinitionError;

struct RecordedDefinition {
  std::string path;
  std::vector<std::string> include_dirs;
};

class DefinitionLoader final : public service::Definitions {
 public:
  // `inline_dir` is where inline definitions are written (created when
  // first needed). All references must outlive the loader.
  DefinitionLoader(dccl::Codec& codec, queue::QueueManager& queues, store::GroupCommitWriter& writer,
                   std::string inline_dir);

  // Start-up, before the store's writer takes the connection.
  static std::vector<RecordedDefinition> read_recorded(store::Database& db);
  // Start-up, before queues exist: loads what read_recorded returned. A file
  // that no longer loads is logged and skipped (its messages are then
  // dropped at restore, each with an event).
  static void load_recorded(dccl::Codec& codec, const std::vector<RecordedDefinition>& recorded);

  // Loads the request's files in order, makes queues for new types and
  // records the files. The caller must have the codec and queues to itself
  // (core thread, no Submit in progress). Throws DefinitionError.
  std::vector<const dccl::TypeInfo*> load(const v1::LoadDefinitionsRequest& request) override;

  const std::string& inline_dir() const { return inline_dir_; }

 private:
  // Writes the text under inline_dir (*fresh: it was not there before).
  RecordedDefinition write_inline(const v1::InlineDefinition& definition,
                                  const std::vector<std::string>& include_dirs, bool* fresh);
  void check_exists(const std::string& path, const std::vector<std::string>& include_dirs) const;
  void record(const RecordedDefinition& definition);
  std::string display_name(const std::string& path) const;

  dccl::Codec& codec_;
  queue::QueueManager& queues_;
  store::GroupCommitWriter& writer_;
  std::string inline_dir_;
};

}  // namespace acomms::node
