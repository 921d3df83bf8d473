// The one transmit and receive sequence every driver runs
// (link/driver_sequence.h), on a recording medium: polls, the data request
// and its limits, "nothing to send", failures reported once, software ACKs
// only for DATA to us that asks for one, and poll answers.

#include "link/driver_sequence.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "link/rate_table.h"

namespace acomms::link {
namespace {

using v1::ModemTransmission;

constexpr int32_t kOwnId = 1;

struct Sent {
  ModemTransmission transmission;
  bool report = false;
};

struct Result {
  ModemTransmission transmission;
  bool ok = false;
  std::string error;
};

class DriverSequenceTest : public ::testing::Test {
 protected:
  DriverSequence make(DriverSequence::Options options = {"test modem 1", kOwnId}) {
    return DriverSequence(std::move(options), {[this](const ModemTransmission& tx, bool report) {
                            sent_.push_back({tx, report});
                            return medium_error_;
                          }});
  }
  DriverCallbacks callbacks() {
    DriverCallbacks c;
    c.on_receive = [this](const ModemTransmission& rx) { received_.push_back(rx); };
    c.on_data_request = [this](ModemTransmission* tx) {
      requests_.push_back(*tx);
      for (const auto& frame : frames_) tx->add_frame(frame);
    };
    c.on_transmit_result = [this](const ModemTransmission& tx, bool ok, const std::string& error) {
      results_.push_back({tx, ok, error});
    };
    return c;
  }
  static ModemTransmission data(int32_t src, int32_t dest, int frames, bool ack_requested) {
    ModemTransmission tx;
    tx.set_type(ModemTransmission::DATA);
    tx.set_src(src);
    tx.set_dest(dest);
    tx.set_rate(1);
    tx.set_ack_requested(ack_requested);
    for (int i = 0; i < frames; ++i) tx.add_frame("frame" + std::to_string(i));
    return tx;
  }
  // What the MAC asks for in its own slot: our DATA, the queues choose dest.
  static ModemTransmission own_slot(int32_t rate = 1) {
    ModemTransmission tx;
    tx.set_type(ModemTransmission::DATA);
    tx.set_src(kOwnId);
    tx.set_dest(-1);
    tx.set_rate(rate);
    return tx;
  }

  std::string medium_error_;
  std::vector<std::string> frames_{"a", "b"};
  std::vector<Sent> sent_;
  std::vector<ModemTransmission> received_;
  std::vector<ModemTransmission> requests_;
  std::vector<Result> results_;
};

// ------------------------------------------------------------ transmitting

TEST_F(DriverSequenceTest, NotStartedIsADriverErrorNamingTheDriver) {
  DriverSequence sequence = make();
  try {
    sequence.transmit(own_slot());
    FAIL() << "transmitted while not started";
  } catch (const DriverError& e) {
    EXPECT_EQ(std::string(e.what()), "test modem 1 is not started");
  }
  EXPECT_THROW(sequence.check_running(), DriverError);
  sequence.start(callbacks());
  EXPECT_NO_THROW(sequence.check_running());
  sequence.stop();
  EXPECT_THROW(sequence.transmit(own_slot()), DriverError);
  EXPECT_TRUE(sent_.empty());
}

TEST_F(DriverSequenceTest, PollOfARemoteNodeIsAFramelessDataUnderItsId) {
  DriverSequence sequence = make();
  sequence.start(callbacks());
  ModemTransmission poll = data(/*src=*/3, /*dest=*/kOwnId, /*frames=*/1, /*ack_requested=*/true);
  sequence.transmit(poll);
  ASSERT_EQ(sent_.size(), 1u);
  EXPECT_EQ(sent_[0].transmission.type(), ModemTransmission::DATA);
  EXPECT_EQ(sent_[0].transmission.src(), 3);
  EXPECT_EQ(sent_[0].transmission.dest(), kOwnId);
  EXPECT_EQ(sent_[0].transmission.frame_size(), 0);
  EXPECT_TRUE(sent_[0].report) << "the MAC waits for the poll's result";
  EXPECT_TRUE(requests_.empty()) << "a poll asks the queues for nothing";
  EXPECT_TRUE(results_.empty()) << "success is the driver's to report once sent";
}

TEST_F(DriverSequenceTest, OwnDataTakesTheRateLimitsAndTheQueuesFramesAndDefaultsToBroadcast) {
  DriverSequence sequence = make();
  sequence.start(callbacks());
  sequence.transmit(own_slot(/*rate=*/1));
  const ModemRate* rate = find_rate(1);
  ASSERT_EQ(requests_.size(), 1u);
  EXPECT_EQ(requests_[0].max_num_frames(), rate->max_num_frames);
  EXPECT_EQ(requests_[0].max_frame_bytes(), rate->max_frame_bytes);
  EXPECT_EQ(requests_[0].src(), kOwnId);
  ASSERT_EQ(sent_.size(), 1u);
  EXPECT_EQ(sent_[0].transmission.frame_size(), 2);
  EXPECT_EQ(sent_[0].transmission.frame(1), "b");
  EXPECT_EQ(sent_[0].transmission.dest(), 0) << "the queues chose nobody: broadcast";
  EXPECT_TRUE(sent_[0].report);
}

TEST_F(DriverSequenceTest, LimitOverridesReplaceTheRateTable) {
  DriverSequence sequence = make({"test modem 1", kOwnId, /*max_frame_bytes=*/1000, /*max_num_frames=*/3});
  sequence.start(callbacks());
  sequence.transmit(own_slot(/*rate=*/0));
  ASSERT_EQ(requests_.size(), 1u);
  EXPECT_EQ(requests_[0].max_frame_bytes(), 1000u);
  EXPECT_EQ(requests_[0].max_num_frames(), 3u);
}

TEST_F(DriverSequenceTest, DataRequestWithoutFramesIsNothingToSend) {
  frames_.clear();
  DriverSequence sequence = make();
  sequence.start(callbacks());
  sequence.transmit(own_slot());
  EXPECT_TRUE(sent_.empty()) << "nothing goes on the medium";
  ASSERT_EQ(results_.size(), 1u);
  EXPECT_FALSE(results_[0].ok);
  EXPECT_EQ(results_[0].error, "nothing to send: the data request gave no frames");
}

TEST_F(DriverSequenceTest, FramesOverTheRateLimitAreNotSent) {
  frames_ = {std::string(find_rate(1)->max_frame_bytes + 1, 'x')};
  DriverSequence sequence = make();
  sequence.start(callbacks());
  sequence.transmit(own_slot(1));
  EXPECT_TRUE(sent_.empty());
  ASSERT_EQ(results_.size(), 1u);
  EXPECT_FALSE(results_[0].ok);
  EXPECT_EQ(results_[0].error.rfind("frame 0 has ", 0), 0u) << results_[0].error;
}

TEST_F(DriverSequenceTest, UnknownRateFailsBeforeTheDataRequest) {
  DriverSequence sequence = make();
  sequence.start(callbacks());
  sequence.transmit(own_slot(/*rate=*/9));
  EXPECT_TRUE(requests_.empty());
  ASSERT_EQ(results_.size(), 1u);
  EXPECT_EQ(results_[0].error, "rate 9 is not in 0..5");
}

TEST_F(DriverSequenceTest, MediumFailureIsReportedOnce) {
  medium_error_ = "busy transmitting";
  DriverSequence sequence = make();
  sequence.start(callbacks());
  sequence.transmit(own_slot());
  ModemTransmission other;
  other.set_type(ModemTransmission::ACK);
  other.set_src(kOwnId);
  sequence.transmit(other);
  ASSERT_EQ(results_.size(), 2u);
  EXPECT_FALSE(results_[0].ok);
  EXPECT_EQ(results_[0].error, "busy transmitting");
  EXPECT_EQ(results_[1].transmission.type(), ModemTransmission::ACK) << "non-DATA goes out as is";
  EXPECT_FALSE(results_[1].ok);
}

TEST_F(DriverSequenceTest, ReportGoesToTheCallbackOnlyWhileStarted) {
  DriverSequence sequence = make();
  sequence.report(own_slot(), true, "");
  sequence.start(callbacks());
  sequence.report(own_slot(), true, "");
  ASSERT_EQ(results_.size(), 1u);
  EXPECT_TRUE(results_[0].ok);
}

// -------------------------------------------------------------- receiving

TEST_F(DriverSequenceTest, DataToUsWithAckRequestedIsAcknowledgedInSoftware) {
  DriverSequence sequence = make();
  sequence.start(callbacks());
  sequence.on_received(data(/*src=*/2, /*dest=*/kOwnId, /*frames=*/3, /*ack_requested=*/true));
  ASSERT_EQ(received_.size(), 1u);
  ASSERT_EQ(sent_.size(), 1u);
  const ModemTransmission& ack = sent_[0].transmission;
  EXPECT_EQ(ack.type(), ModemTransmission::ACK);
  EXPECT_EQ(ack.src(), kOwnId);
  EXPECT_EQ(ack.dest(), 2);
  EXPECT_EQ(ack.acked_frame_size(), 3);
  EXPECT_EQ(ack.acked_frame(2), 2u);
  EXPECT_FALSE(sent_[0].report) << "nobody waits for an ACK's result";
}

// The ACK promises the message is safe: it waits until what on_receive
// passed on is durable, then still waits for the medium.
TEST_F(DriverSequenceTest, SoftwareAckWaitsUntilTheReceiptIsDurable) {
  DriverSequence sequence = make();
  DriverCallbacks c = callbacks();
  std::vector<std::function<void()>> durable;
  c.after_receipt_durable = [&](std::function<void()> then) {
    EXPECT_EQ(received_.size(), 1u) << "asked for only after the packet went to on_receive";
    durable.push_back(std::move(then));
  };
  sequence.start(c);
  std::vector<std::function<void()>> waiting;
  DriverSequence::Heard heard{2, [&](std::function<void()> answer) { waiting.push_back(std::move(answer)); }};
  sequence.on_received(data(2, kOwnId, 2, /*ack_requested=*/true), heard);
  ASSERT_EQ(durable.size(), 1u);
  EXPECT_TRUE(waiting.empty()) << "not even queued for the medium before the commit";
  EXPECT_TRUE(sent_.empty());
  durable[0]();
  EXPECT_TRUE(sent_.empty()) << "then it waits for the medium";
  ASSERT_EQ(waiting.size(), 1u);
  waiting[0]();
  ASSERT_EQ(sent_.size(), 1u);
  EXPECT_EQ(sent_[0].transmission.type(), ModemTransmission::ACK);
  EXPECT_EQ(sent_[0].transmission.dest(), 2);
  EXPECT_EQ(sent_[0].transmission.acked_frame_size(), 2);
  // Nothing to acknowledge, nothing to wait for.
  sequence.on_received(data(2, kOwnId, 1, /*ack_requested=*/false), heard);
  EXPECT_EQ(durable.size(), 1u);
}

TEST_F(DriverSequenceTest, NoAckWhenTheCommitEndsAfterTheDriverStoppedOrWentAway) {
  std::vector<std::function<void()>> durable;
  DriverCallbacks c = callbacks();
  c.after_receipt_durable = [&](std::function<void()> then) { durable.push_back(std::move(then)); };
  {
    DriverSequence sequence = make();
    sequence.start(c);
    sequence.on_received(data(2, kOwnId, 1, true));
    sequence.stop();
    ASSERT_EQ(durable.size(), 1u);
    durable[0]();
    EXPECT_TRUE(sent_.empty()) << "stopped: nothing more goes out";
    sequence.start(c);
    sequence.on_received(data(2, kOwnId, 1, true));
    ASSERT_EQ(durable.size(), 2u);
  }
  durable[1]();  // the sequence (and its driver) are gone
  EXPECT_TRUE(sent_.empty());
}

TEST_F(DriverSequenceTest, NoAckForBroadcastForOthersOrWithoutAckRequested) {
  DriverSequence sequence = make();
  sequence.start(callbacks());
  sequence.on_received(data(2, /*dest=*/0, 1, /*ack_requested=*/true));
  sequence.on_received(data(2, /*dest=*/3, 1, /*ack_requested=*/true));
  sequence.on_received(data(2, /*dest=*/kOwnId, 1, /*ack_requested=*/false));
  EXPECT_TRUE(sent_.empty());
  EXPECT_EQ(received_.size(), 3u) << "DATA for anyone is reported: the queues filter by dest";
}

TEST_F(DriverSequenceTest, ModemThatAcksInHardwareGetsNoSoftwareAck) {
  DriverSequence::Options options{"micromodem 1", kOwnId};
  options.software_acks = false;
  DriverSequence sequence = make(options);
  sequence.start(callbacks());
  sequence.on_received(data(2, kOwnId, 1, true));
  EXPECT_EQ(received_.size(), 1u);
  EXPECT_TRUE(sent_.empty());
}

TEST_F(DriverSequenceTest, AcksAreReportedOnlyToTheirDestination) {
  DriverSequence sequence = make();
  sequence.start(callbacks());
  ModemTransmission ack;
  ack.set_type(ModemTransmission::ACK);
  ack.set_src(2);
  ack.set_dest(3);
  sequence.on_received(ack);
  ack.set_dest(kOwnId);
  sequence.on_received(ack);
  ASSERT_EQ(received_.size(), 1u);
  EXPECT_EQ(received_[0].dest(), kOwnId);
}

TEST_F(DriverSequenceTest, PollForUsIsAnsweredWithOurDataAndNotReported) {
  DriverSequence sequence = make();
  sequence.start(callbacks());
  ModemTransmission poll = data(/*src=*/kOwnId, /*dest=*/4, /*frames=*/0, /*ack_requested=*/true);
  sequence.on_received(poll);
  EXPECT_TRUE(received_.empty());
  ASSERT_EQ(requests_.size(), 1u);
  ASSERT_EQ(sent_.size(), 1u);
  EXPECT_EQ(sent_[0].transmission.src(), kOwnId);
  EXPECT_EQ(sent_[0].transmission.dest(), 4);
  EXPECT_TRUE(sent_[0].transmission.ack_requested());
  EXPECT_EQ(sent_[0].transmission.frame_size(), 2);
  EXPECT_TRUE(sent_[0].report);
}

TEST_F(DriverSequenceTest, WithTheSenderKnownDataUnderAnotherIdIsAPoll) {
  DriverSequence sequence = make();
  sequence.start(callbacks());
  DriverSequence::Heard from_two{2, nullptr};
  // Node 2 polls node 3: not ours to answer, and not DATA for the queues.
  sequence.on_received(data(/*src=*/3, kOwnId, /*frames=*/1, false), from_two);
  EXPECT_TRUE(received_.empty());
  EXPECT_TRUE(sent_.empty());
  // Node 2 polls us.
  sequence.on_received(data(/*src=*/kOwnId, 2, 0, false), from_two);
  ASSERT_EQ(sent_.size(), 1u);
  EXPECT_EQ(sent_[0].transmission.src(), kOwnId);
}

TEST_F(DriverSequenceTest, AnswersWaitUntilTheMediumIsFree) {
  DriverSequence sequence = make();
  sequence.start(callbacks());
  std::vector<std::function<void()>> waiting;
  DriverSequence::Heard heard{2, [&](std::function<void()> answer) { waiting.push_back(std::move(answer)); }};
  sequence.on_received(data(2, kOwnId, 1, /*ack_requested=*/true), heard);
  sequence.on_received(data(kOwnId, 2, 0, false), heard);
  EXPECT_EQ(received_.size(), 1u) << "reported at once";
  EXPECT_TRUE(sent_.empty()) << "ACK and poll answer wait";
  ASSERT_EQ(waiting.size(), 2u);
  for (auto& answer : waiting) answer();
  ASSERT_EQ(sent_.size(), 2u);
  EXPECT_EQ(sent_[0].transmission.type(), ModemTransmission::ACK);
  EXPECT_EQ(sent_[1].transmission.type(), ModemTransmission::DATA);
  EXPECT_EQ(sent_[1].transmission.frame_size(), 2);
}

TEST_F(DriverSequenceTest, NothingIsHeardAfterStop) {
  DriverSequence sequence = make();
  sequence.start(callbacks());
  sequence.stop();
  sequence.on_received(data(2, kOwnId, 1, true));
  EXPECT_TRUE(received_.empty());
  EXPECT_TRUE(sent_.empty());
}

}  // namespace
}  // namespace acomms::link
