#pragma once
// Iridium DirectIP's byte layouts, as the shore endpoint meets them
// (../shared/spec/iridium-sbd.md §9): the MO messages the gateway pushes to
// us, the MO confirmation we may answer, the MT messages we submit and the
// MT confirmation the gateway answers them with.
//
// The problem: these bytes come from a socket anyone on the network can
// reach. The decision: one parser, pure functions over a complete message
// (prefix included), that never trusts a length: every IE must fit what is
// left, the IEs must add up to the overall length exactly, and each known IE
// must have its spec length, or the whole message is refused with a reason
// a person can read. Unknown IEIs are skipped by their length and counted
// (spec §9.1). Nothing here touches sockets, time or the daemon, so the
// fuzz target (tests/fuzz/directip_mo_fuzz.cpp) runs it alone.
//
// Every multi-byte integer is big-endian; there is no padding.
//
// Thread-safe: pure functions of their arguments.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace acomms::drivers::directip {

inline constexpr uint8_t kProtocolRevision = 1;
inline constexpr size_t kPrefixBytes = 3;  // revision, overall length (2)
// The largest overall length read before refusing (our choice, spec §9.1:
// the largest legitimate message is under 400 bytes).
inline constexpr size_t kMaxOverallLength = 2048;
inline constexpr size_t kMaxMoPayload = 340;  // 9602/9603 (spec §6.1)
inline constexpr size_t kMaxMtPayload = 270;
inline constexpr size_t kImeiDigits = 15;

// Information element identifiers (spec §9.2, §9.3).
inline constexpr uint8_t kMoHeaderIei = 0x01;
inline constexpr uint8_t kMoPayloadIei = 0x02;
inline constexpr uint8_t kMoLocationIei = 0x03;
inline constexpr uint8_t kMoConfirmationIei = 0x05;
inline constexpr uint8_t kMtHeaderIei = 0x41;
inline constexpr uint8_t kMtPayloadIei = 0x42;
inline constexpr uint8_t kMtConfirmationIei = 0x44;

// MT disposition flags (spec §9.3.1).
inline constexpr uint16_t kFlushMtQueue = 0x0001;
inline constexpr uint16_t kSendRingAlert = 0x0002;
inline constexpr uint16_t kAssignMtmsn = 0x0020;

// The overall length N of a message from its first 3 bytes (revision 1,
// N ≤ kMaxOverallLength), or nullopt with `error` set.
std::optional<uint16_t> parse_prefix(std::string_view prefix, std::string* error);

// MO header, IEI 0x01 (spec §9.2.1).
struct MoHeader {
  uint32_t cdr_reference = 0;
  std::string imei;            // 15 ASCII digits
  uint8_t session_status = 0;  // 0, 1, 2: the MO got through; ≥ 10: failed (no payload)
  uint16_t momsn = 0;
  uint16_t mtmsn = 0;          // the MT offered in this session; 0: none
  uint32_t session_time = 0;   // UTC seconds since 1970
};

// MO location, IEI 0x03 (spec §9.2.3): the network's estimate, not GPS.
struct MoLocation {
  double latitude_deg = 0;   // south negative
  double longitude_deg = 0;  // west negative
  uint32_t cep_km = 0;
};

struct MoMessage {
  MoHeader header;
  std::string payload;  // empty: a mailbox check or a failed session
  std::optional<MoLocation> location;
  // IEs skipped: unknown IEIs, and a location IE that was not usable
  // (a length other than 11, or values out of range), which is optional
  // and never worth refusing the payload for.
  uint32_t unknown_ies = 0;
  uint32_t unusable_locations = 0;
};

// Whether a session status delivered an MO (0, 1, 2; spec §9.2.1).
bool mo_session_succeeded(uint8_t session_status);

// Parses one whole MO message (the prefix and N bytes). nullopt with
// `error` set ("IE 0x02 claims 400 bytes, 12 are left") when refused.
std::optional<MoMessage> parse_mo(std::string_view message, std::string* error);

// The MO confirmation (IEI 0x05, spec §9.2.4): 01 00 04 05 00 01 <status>.
std::string build_mo_confirmation(bool received);

// An MT submission (spec §9.3.1, §9.3.2).
struct MtSubmission {
  uint32_t client_id = 0;  // with kAssignMtmsn: 1..65535, and the MT's MTMSN
  std::string imei;
  uint16_t flags = 0;
  std::string payload;     // 1..kMaxMtPayload bytes; none with kSendRingAlert
};

// The bytes of `mt`, or "" with `error` set when the submission breaks a
// rule the gateway would refuse it for (IMEI, payload size, flags).
std::string build_mt(const MtSubmission& mt, std::string* error);

// MT confirmation, IEI 0x44 (spec §9.3.4).
struct MtConfirmation {
  uint32_t client_id = 0;
  std::string imei;
  uint32_t auto_id = 0;  // the gateway's record id, 0 on error
  int16_t status = 0;    // ≥ 0 queued (position), < 0 refused
};

// Parses one whole MT confirmation message; nullopt with `error` set.
std::optional<MtConfirmation> parse_mt_confirmation(std::string_view message, std::string* error);

// What to do about an MT status (spec §9.3.4).
enum class MtOutcome {
  kQueued,      // ≥ 0: the MT is at the gateway
  kRetryLater,  // −5 queue full, −6 resources unavailable
  kRefused,     // anything else: configuration or a bug; retrying soon will not help
};
MtOutcome mt_outcome(int16_t status);
// The status as a person reads it: "-2 (IMEI not provisioned)".
std::string mt_status_text(int16_t status);

}  // namespace acomms::drivers::directip
