#pragma once
// A received transmission's link figures (who transmitted, at what rate,
// and what the modem measured), as a subscriber sees them with each message
// it carried and as the event log keeps them.
//
// One conversion, used by both: the live message (service) and the stored
// event (link controller -> queue) must never disagree, or a replayed
// message would carry different figures from the same message seen live.
// Any thread (a pure function).

#include "acomms/v1/link_figures.pb.h"
#include "acomms/v1/modem_transmission.pb.h"

namespace acomms::link {

// The figures of a received DATA transmission. Only what the driver
// reported is set (ReceptionFigures' fields it has no LinkFigures field for,
// e.g. $CACST's psk_error, are left out).
v1::LinkFigures link_figures(const v1::ModemTransmission& transmission);

}  // namespace acomms::link
