#pragma once
// Lines copied verbatim from /work/shared/spec/micromodem-nmea.md (the
// project's own spec), checksums included, for the NMEA tests and as fuzz
// seeds. Host lines ($CC...) must re-serialise byte for byte.

#include <string_view>
#include <vector>

namespace acomms::micromodem::spec {

// §2.1: "Other verified real lines", and the worked example.
inline const std::vector<std::string_view> kRealLines = {
    "$CACFG,SRC,1*33",
    "$CAREV,181807,AUV,2.0.27087*12",
    "$CAREV,181807,COPROC,0.20.0.56*45",
    "$CAREV,000052,AUV,0.93.0.09*07",
    "$CATXF,2*56",
    "$CATXF,28*6E",
    "$CAXST,7,20250606,230103.000935,3,0,200,5000,25000,1,0,1,0,0,1,5,2,25000*53",
    "$CACST,8,0,20250606230123.348554,06,32767,45,0102,0123,07,00,00,00,00,1,001,000,0,5,1,0,150,"
    "26.0,9.48,-100,-6.48,-01,0.01,51,25000,5000,0,-1,-1,00*4A",
    "$CACST,1,153026.0000,0,4105,30,0318,0193,10,00,00,01,01,2,004,004,3,3,3,1,154,09,08,10,-6,"
    "000,0.0,4125000,5000*5B",
};

// §8.1: unicast, rate 0, acknowledged (1 → 2), every line the spec gives
// in full, in table order. Modem 1's lines and modem 2's are interleaved
// as in the table.
inline const std::vector<std::string_view> kUnicastRate0 = {
    "$CCCYC,0,1,2,0,1,1*5A",         // 1 host of modem 1
    "$CACYC,0,1,2,0,1,1*58",         // 2
    "$CATXP,2*40",                   // 3
    "$CARXP,0*44",                   // 4 modem 2
    "$CATXF,2*56",                   // 5
    "$CACYC,0,1,2,0,1,1*58",         // 7 modem 2
    "$CADRQ,120001,1,2,1,32,1*45",   // 8
    "$CCTXD,1,2,1,48656C6C6F*05",    // 9 host of modem 1
    "$CATXD,1,2,1,5*4D",             // 10
    "$CATXP,5*47",                   // 11
    "$CARXP,0*44",                   // 12 modem 2
    "$CATXF,5*51",                   // 13
    "$CARXD,1,2,1,1,48656C6C6F*1C",  // 14 modem 2
    "$CATXP,2*40",                   // 15 modem 2
    "$CARXP,0*44",                   // 16
    "$CATXF,2*56",                   // 17 modem 2
    "$CAACK,2,1,1,1*48",             // 18
};

// §8.2: third-party cycle, master 1 polls 2 to send to 1 (rate 1, 2 frames).
inline const std::vector<std::string_view> kThirdParty = {
    "$CCCYC,0,2,1,1,1,2*58",       // 1 host of modem 1
    "$CACYC,0,2,1,1,1,2*5A",       // 2
    "$CACYC,0,2,1,1,1,2*5A",       // 3 modem 2
    "$CADRQ,120101,2,1,1,64,1*47", // 4 modem 2
    "$CCTXD,2,1,1,0102*79",        //   host of modem 2
    "$CATXD,2,1,1,2*4A",
    "$CADRQ,120101,2,1,1,64,2*44", // 5
    "$CCTXD,2,1,1,*7A",            //   host of modem 2: no more data
    "$CATXD,2,1,1,0*48",
    "$CARXD,2,1,1,1,0102*60",      // 7 modem 1
    "$CARXD,2,1,1,2,*60",
    "$CAACK,1,2,1,1*48",           // 9 modem 2
};

// §8.3: broadcast (2 → all, rate 1, 1 frame). The spec gives these lines
// without checksums (a host may omit them; §2.3).
inline const std::vector<std::string_view> kBroadcastWithoutChecksums = {
    "$CCCYC,0,2,0,1,0,1",
    "$CACYC,0,2,0,1,0,1",
    "$CCTXD,2,0,0,CAFE",
    "$CATXD,2,0,0,2",
    "$CARXP,1",
    "$CARXD,2,0,0,1,CAFE",
};

// §8.4 ping, §8.5 LBL: not typed by this library, but well-formed lines
// that must parse as sentences.
inline const std::vector<std::string_view> kPingAndLbl = {
    "$CCMPC,1,2*5D",
    "$CAMPC,1,2*5F",
    "$CAMPA,1,2*5D",
    "$CAMPR,2,1,1.0000*7D",
    "$CCCFG,TAT,50*06",
    "$CACFG,TAT,50*04",
    "$CCPNT,25000,5,5,4000,26000,27000,0,0,1*65",
    "$SNTTA,0.5007,0.9930,,,120301.25*59",
    "$CCPDT,1,2,0,0,4000,1,1,0,0*6B",
    "$SNTTA,0.3335,0.6683,,,120311.00*53",
};

}  // namespace acomms::micromodem::spec
