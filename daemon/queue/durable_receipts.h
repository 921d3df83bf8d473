#pragma once
// When may a receiver acknowledge what it heard? Only once the received
// events are committed: an ACK makes the sender forget its copy, so an ACK
// sent earlier leaves a window (hearing to commit) where a crash loses the
// message for good. This is the rule the link's software ACKs wait on
// (link::DriverCallbacks::after_receipt_durable); tests/integration
// queue_crash_test kills a receiver to show it holds.
//
// Threads: call the returned functions on the core thread, where the events
// they cover are recorded; their callbacks run on the journal's thread, one at
// a time, in order (durable_receipts posts `then` back to the core).

#include <functional>

#include "queue/message_journal.h"

namespace acomms::queue {

using Task = std::function<void()>;
// Hands a task to the core thread (core::EventLoop::post).
using PostToCore = std::function<void(Task)>;
// Runs `then` on the core thread once every event given to the journal so
// far is committed; never if any event recorded since the previous call
// failed to commit (logged: the ACK is withheld and the sender sends again,
// even when the failure was another event's: withholding costs a resend,
// a wrong ACK costs the message).
using AfterReceiptsDurable = std::function<void(Task then)>;

// `journal` must outlive the function returned, and `post` must be usable
// from the journal's commit thread.
AfterReceiptsDurable durable_receipts(MessageJournal& journal, PostToCore post);

// The check under it, for any caller that must know its events are stored,
// not only done: like journal.when_committed(committed), but `committed`
// also gets an error when an event recorded since this chain's previous
// call failed in an earlier batch (MessageJournal::events_not_stored).
// Each use keeps a chain of its own, or one would answer for another's
// failures. Its calls' callbacks run in order on the journal's thread.
using WhenStored = std::function<void(MessageJournal::Committed committed)>;
WhenStored when_stored(MessageJournal& journal);

}  // namespace acomms::queue
