#include "queue_command.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "api_client.h"
#include "global_options.h"
#include "output.h"
#include "rpc_error.h"
#include "util/seconds.h"

namespace acomms::cli {
namespace {

struct QueueOptions {
  std::string type;
  std::vector<std::string> types;
  uint32_t limit = 0;
  int64_t message_id = 0;
  std::string reason;
};

// A gateway's note before the message: "(waits: no route to node 5)", or
// where it goes next, "(next hop 2 on sat)".
std::string routing_text(const v1::QueuedMessage& m) {
  std::string note;
  if (!m.waiting().empty()) {
    note = "(waits: " + m.waiting() + ") ";
  } else if (m.next_hop() != 0 && m.next_hop() != m.dest()) {
    note = "(next hop " + std::to_string(m.next_hop()) + " on " + m.next_link() + ") ";
  } else if (m.next_hop() != 0) {
    note = "(neighbour, on " + m.next_link() + ") ";
  }
  return note + m.json();
}

void run_ls(const GlobalOptions& global, const QueueOptions& options) {
  v1::ListQueuedRequest request;
  request.set_type(options.type);
  request.set_limit(options.limit);
  ApiClient client(global);
  v1::ListQueuedResponse response = client.call(&v1::Acomms::Stub::ListQueued, request);
  if (global.json) {
    print_json(response);
    return;
  }
  std::printf("%-8s %-28s %-8s %-25s %9s %5s %-9s %s\n", "ID", "TYPE", "SRC>DEST", "SUBMITTED", "EXPIRES", "BYTES",
              "STATE", "MESSAGE");
  const double now = util::unix_seconds_now();
  for (const v1::QueuedMessage& m : response.messages()) {
    std::string expires = m.expires_at() > 0 ? std::to_string(static_cast<long long>(m.expires_at() - now)) + "s" : "-";
    std::printf("%-8lld %-28s %-8s %-25s %9s %5u %-9s %s\n", static_cast<long long>(m.message_id()), m.type().c_str(),
                route_text(m.src(), m.dest()).c_str(), utc_text(m.submitted_at()).c_str(), expires.c_str(),
                m.encoded_bytes(), m.in_flight() ? "in-flight" : "queued", routing_text(m).c_str());
  }
  if (response.truncated()) std::printf("(more messages are queued; raise --limit to see them)\n");
}

void run_cancel(const GlobalOptions& global, const QueueOptions& options) {
  v1::CancelRequest request;
  request.set_message_id(options.message_id);
  request.set_reason(options.reason);
  ApiClient client(global);
  v1::CancelResponse response = client.call(&v1::Acomms::Stub::Cancel, request);
  if (global.json) {
    print_json(response);
  } else {
    std::printf("cancelled message %lld\n", static_cast<long long>(options.message_id));
  }
}

void run_flush(const GlobalOptions& global, const QueueOptions& options) {
  v1::FlushRequest request;
  request.set_type(options.type);
  ApiClient client(global);
  v1::FlushResponse response = client.call(&v1::Acomms::Stub::Flush, request);
  if (global.json) {
    print_json(response);
  } else {
    std::printf("removed %u message(s) of %s\n", response.removed(), options.type.c_str());
  }
}

std::string on_full_text(const v1::QueuePolicy& policy) {
  return policy.on_full() == v1::QueuePolicy::REFUSE_NEW ? "refuse" : "drop-old";
}

void run_stats(const GlobalOptions& global, const QueueOptions& options) {
  v1::QueueStatsRequest request;
  for (const std::string& type : options.types) request.add_types(type);
  ApiClient client(global);
  v1::QueueStatsResponse response = client.call(&v1::Acomms::Stub::QueueStats, request);
  if (global.json) {
    print_json(response);
    return;
  }
  std::printf("%-28s %6s %5s %6s %8s %7s %6s %6s %7s %7s %7s %7s %8s %9s %7s  %-14s %s\n", "TYPE", "ID", "SIZE",
              "FLIGHT", "PRIORITY", "QUEUED", "SENT", "ACKED", "EXPIRED", "DROPPED", "REFUSED", "RETRIED", "RECEIVED",
              "DELIVERED", "EXP-FAR", "POLICY", "LAST SENT");
  for (const v1::QueueStatsEntry& q : response.queues()) {
    std::string policy = std::to_string(q.policy().max_queue()) + " " + on_full_text(q.policy());
    std::printf("%-28s %6d %5u %6u %8.3g %7llu %6llu %6llu %7llu %7llu %7llu %7llu %8llu %9llu %7llu  %-14s %s\n",
                q.type().c_str(), q.dccl_id(), q.size(), q.in_flight(), q.priority(),
                static_cast<unsigned long long>(q.queued()), static_cast<unsigned long long>(q.sent()),
                static_cast<unsigned long long>(q.acked()), static_cast<unsigned long long>(q.expired()),
                static_cast<unsigned long long>(q.dropped()), static_cast<unsigned long long>(q.refused()),
                static_cast<unsigned long long>(q.retried()), static_cast<unsigned long long>(q.received()),
                static_cast<unsigned long long>(q.delivered()), static_cast<unsigned long long>(q.expired_remote()),
                policy.c_str(), utc_text(q.last_sent()).c_str());
  }
}

}  // namespace

void add_queue_command(CLI::App& app, const GlobalOptions& global) {
  static QueueOptions options;
  CLI::App* queue = app.add_subcommand(
      "queue", "Inspect and trim the queues of messages waiting for a slot on the link");
  queue->require_subcommand(1);
  queue->footer("Example:\n  acommsctl queue ls && acommsctl queue stats");

  CLI::App* ls = queue->add_subcommand("ls", "List the messages waiting to be sent (or acknowledged)");
  ls->add_option("TYPE", options.type, "Only this type")->type_name("");
  ls->add_option("--limit", options.limit, "At most this many (default 1000, most 10000)")->type_name("N");
  ls->footer(
      "Columns: message id, type, source>destination, when submitted, seconds until it expires, encoded "
      "bytes on the wire, queued or in-flight (sent, awaiting its ack), and the message. On a gateway (config "
      "`routing`) the message is preceded by why it waits, \"(waits: no route to node 5)\", or by where its "
      "route takes it next, \"(next hop 2 on sat)\" (\"(neighbour, on acoustic)\": its destination is heard "
      "there).\n\n"
      "Example:\n  acommsctl queue ls gv.NavigationReport --limit 20");
  ls->callback([&global] { run_ls(global, options); });

  CLI::App* cancel = queue->add_subcommand("cancel", "Remove one queued message before it is sent");
  cancel->add_option("ID", options.message_id, "Message id, as `send` printed it")->required()->type_name("");
  cancel->add_option("--reason", options.reason, "Why, for the event log (default \"cancelled by client\")")
      ->type_name("TEXT");
  cancel->footer(
      "A message in flight is no longer retried. The event log records a 'dropped' event with the reason.\n\n"
      "Example:\n  acommsctl queue cancel 42 --reason \"superseded by newer fix\"");
  cancel->callback([&global] { run_cancel(global, options); });

  CLI::App* flush = queue->add_subcommand("flush", "Remove every queued message of one type.");
  flush->add_option("TYPE", options.type, "The type to empty")->required()->type_name("");
  flush->footer("Example:\n  acommsctl queue flush gv.NavigationReport");
  flush->callback([&global] { run_flush(global, options); });

  CLI::App* stats = queue->add_subcommand("stats", "Per-queue sizes, priorities, counters and policy");
  stats->add_option("TYPE", options.types, "Only these types (default: every queue)")->type_name("");
  stats->footer(
      "Per queue: messages held and in flight, priority in the contest for the next frame, counters "
      "since the daemon started (queued, sent, acked, expired, dropped, refused, retried, received; on a "
      "gateway's origin also DELIVERED, routed messages whose end-to-end ack came back, and EXP-FAR, routed "
      "messages reported expired at another node: EXPIRED counts only those whose ttl ran out here), the "
      "max_queue and on_full policy, and when it last sent.\n\n"
      "Example:\n  acommsctl queue stats --json | jq '.queues[] | {type, size, dropped}'");
  stats->callback([&global] { run_stats(global, options); });
}

}  // namespace acomms::cli
