// `acommsctl track SRC --kml FILE`, the real binary, against a stand-in for
// the daemon's Track call: an in-process gRPC server on a unix socket that
// answers a track the test chose. A real daemon only has a track after a
// second daemon streamed one to it (telemetry_two_node_test.cpp, which has
// no datum and so no lat/lon); what is checked here is what acommsctl makes
// of a known answer: the file's exact text, that an XML parser reads it as
// KML, that every coordinate is lon,lat,altitude with altitude = -depth, and
// what an empty track, one position and a track without lat/lon give.

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include "acomms/v1/acomms.grpc.pb.h"
#include "child_process.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;

// Answers Track with `answer`, remembers the request. Every other call is
// the generated UNIMPLEMENTED: acommsctl track must need no other.
class TrackService final : public v1::Acomms::Service {
 public:
  grpc::Status Track(grpc::ServerContext*, const v1::TrackRequest* request, v1::TrackResponse* response) override {
    std::lock_guard lock(mutex_);
    request_ = *request;
    *response = answer_;
    return grpc::Status::OK;
  }
  void answer(v1::TrackResponse answer) {
    std::lock_guard lock(mutex_);
    answer_ = std::move(answer);
  }
  v1::TrackRequest request() {
    std::lock_guard lock(mutex_);
    return request_;
  }

 private:
  std::mutex mutex_;
  v1::TrackResponse answer_;
  v1::TrackRequest request_;
};

telemetry::Position position(double time, double lat, double lon, double depth) {
  telemetry::Position p;
  p.set_src(2);
  p.set_time(time);
  p.set_lat(lat);
  p.set_lon(lon);
  p.set_depth(depth);
  p.set_z(-depth);
  return p;
}

std::string read_file(const fs::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

class AcommsctlTrack : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path("/tmp") / ("acomms-track-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    grpc::ServerBuilder builder;
    builder.AddListeningPort("unix:" + socket(), grpc::InsecureServerCredentials());
    builder.RegisterService(&service_);
    server_ = builder.BuildAndStart();
    ASSERT_NE(server_, nullptr);
  }
  void TearDown() override {
    server_->Shutdown();
    fs::remove_all(dir_);
  }

  std::string socket() const { return (dir_ / "acommsd.sock").string(); }
  fs::path kml() const { return dir_ / "track.kml"; }

  RunResult track(std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"--socket", socket(), "track", "2", "--kml", kml().string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return run(ACOMMSCTL_BINARY, args, (dir_ / "acommsctl").string());
  }

  // The file read by Python's XML parser (expat): its root, and per
  // Placemark geometry the tag and the coordinate tuples, one a line
  // ("LineString -70.5,41.25,-12"); "not well-formed ..." when it does not
  // parse. Python comes with the test dependencies (python3-grpcio).
  RunResult parsed_by_python() {
    static const char* kScript = R"(
import sys, xml.etree.ElementTree as ET
ns = '{http://www.opengis.net/kml/2.2}'
try:
    root = ET.parse(sys.argv[1]).getroot()
except ET.ParseError as e:
    print('not well-formed', e); sys.exit(0)
print(root.tag)
for doc in root.findall(ns + 'Document'):
    print('Document', doc.findtext(ns + 'name'), '|', doc.findtext(ns + 'description'))
    for placemark in doc.findall(ns + 'Placemark'):
        for geometry in placemark:
            if geometry.tag == ns + 'name': continue
            for t in geometry.findtext(ns + 'coordinates').split():
                print(geometry.tag[len(ns):], t)
)";
    return run(ACOMMS_PYTHON3, {"-c", kScript, kml().string()}, (dir_ / "python").string());
  }

  fs::path dir_;
  TrackService service_;
  std::unique_ptr<grpc::Server> server_;
};

// Two positions in a distinct corner of the world (south, west, one at the
// surface): the document byte for byte, lon before lat, altitude -depth.
TEST_F(AcommsctlTrack, KmlOfATinyTrackIsExactlyLonLatAltitudeInALineString) {
  v1::TrackResponse answer;
  *answer.add_positions() = position(1764000000, -33.8712345, 151.2098765, 12.5);
  *answer.add_positions() = position(1764000010, -33.87125, 151.20995, 0);
  service_.answer(answer);
  RunResult result = track();
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(service_.request().src(), 2);
  EXPECT_EQ(result.err, "2 positions written to " + kml().string() + "\n");
  EXPECT_EQ(read_file(kml()),
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n"
            "<Document>\n"
            "<name>acomms track of node 2</name>\n"
            "<Placemark>\n"
            "<name>node 2</name>\n"
            "<LineString>\n"
            "<altitudeMode>absolute</altitudeMode>\n"
            "<coordinates>\n"
            "151.2098765,-33.8712345,-12.5\n"
            "151.20995,-33.87125,0\n"
            "</coordinates>\n"
            "</LineString>\n"
            "</Placemark>\n"
            "</Document>\n"
            "</kml>\n");
}

// A longer track through a real XML parser: well-formed KML, one tuple per
// position, in order, each lon,lat,-depth to the digits printed (10
// significant: under a millimetre of latitude).
TEST_F(AcommsctlTrack, KmlParsesAsXmlWithOneLonLatAltitudeTuplePerPositionInOrder) {
  v1::TrackResponse answer;
  for (int i = 0; i < 50; ++i) {
    *answer.add_positions() = position(1764000000 + 10 * i, 41.52 + 1e-4 * i, -70.67 - 2e-4 * i, 3.0 * (i % 7));
  }
  service_.answer(answer);
  RunResult result = track({"--since", "1764000000"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(service_.request().since(), 1764000000);
  RunResult xml = parsed_by_python();
  ASSERT_EQ(xml.exit_code, 0) << xml.err;
  std::vector<std::string> lines = lines_of(xml.out);
  ASSERT_EQ(lines.size(), 2u + 50u) << xml.out;
  EXPECT_EQ(lines[0], "{http://www.opengis.net/kml/2.2}kml");
  EXPECT_EQ(lines[1], "Document acomms track of node 2 | None");
  for (int i = 0; i < 50; ++i) {
    const telemetry::Position& p = answer.positions(i);
    double lon = 0, lat = 0, altitude = 0;
    char geometry[16] = {};
    ASSERT_EQ(std::sscanf(lines[2 + i].c_str(), "%15s %lf,%lf,%lf", geometry, &lon, &lat, &altitude), 4)
        << lines[2 + i];
    EXPECT_STREQ(geometry, "LineString");
    EXPECT_NEAR(lon, p.lon(), 1e-7) << i;
    EXPECT_NEAR(lat, p.lat(), 1e-7) << i;
    EXPECT_EQ(altitude, -p.depth()) << i;
  }
}

// Nothing received (yet): still a document a viewer opens, saying why it
// is empty, and a line that says so; not an empty LineString.
TEST_F(AcommsctlTrack, EmptyTrackIsAValidDocumentThatSaysNoPositionsAndNoPlacemark) {
  service_.answer({});
  RunResult result = track({"--since", "-1h"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "no positions from node 2 since -1h: " + kml().string() + " is a KML document with no track\n");
  RunResult xml = parsed_by_python();
  ASSERT_EQ(xml.exit_code, 0) << xml.err;
  EXPECT_EQ(lines_of(xml.out), (std::vector<std::string>{"{http://www.opengis.net/kml/2.2}kml",
                                                          "Document acomms track of node 2 | no positions received "
                                                          "from node 2"}));
}

// KML 2.2 wants two coordinates or more in a LineString: one is a Point.
TEST_F(AcommsctlTrack, SinglePositionIsAPoint) {
  v1::TrackResponse answer;
  *answer.add_positions() = position(1764000000, 41.5, -70.25, 100);
  service_.answer(answer);
  RunResult result = track();
  ASSERT_EQ(result.exit_code, 0) << result.err;
  RunResult xml = parsed_by_python();
  ASSERT_EQ(xml.exit_code, 0) << xml.err;
  std::vector<std::string> lines = lines_of(xml.out);
  ASSERT_EQ(lines.size(), 3u) << xml.out;
  EXPECT_EQ(lines[2], "Point -70.25,41.5,-100");
}

// A daemon without telemetry.datum answers x,y only: a usage error that
// points at --csv, and no file (not an empty or half-written one).
TEST_F(AcommsctlTrack, TrackWithoutLatLonIsRefusedAndWritesNoFile) {
  v1::TrackResponse answer;
  telemetry::Position p;
  p.set_src(2);
  p.set_x(10);
  *answer.add_positions() = p;
  service_.answer(answer);
  RunResult result = track();
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("no lat/lon"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("--csv"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(kml()));
}

}  // namespace
}  // namespace acomms::testing
