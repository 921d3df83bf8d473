// BELLHOP-format import: every conformance environment imports; values are
// converted to SI; unsupported options are refused by name.
#include <filesystem>

#include <gtest/gtest.h>

#include "gram/bellhop_import.h"
#include "gram/environment_validation.h"

namespace acomms::gram {
namespace {

const std::string kEnvDir = std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs";

// A minimal valid file; `top`, `bottom` and `run` replace the option lines.
std::string env_text(const std::string& top = "'CVW'", const std::string& bottom = "'A' 0.0",
                     const std::string& run = "'CG'", const std::string& halfspace =
                         "100 1650 0 1.9 0.8 0.0 /") {
  return "'test'\n500\n1\n" + top + "\n0 0.0 100\n0 1500 /\n100 1500 /\n" + bottom + "\n" +
         halfspace + "\n1\n36 /\n25\n2 98 /\n393\n0.2 10 /\n" + run + "\n0\n-89 89 /\n0 101 10.1\n";
}

ImportedEnvironment import(const std::string& text, const SideFileLoader& side = {}) {
  return import_bellhop_env(text, "test.env", side);
}

std::string refusal(const std::string& text, const SideFileLoader& side = {}) {
  try {
    import(text, side);
  } catch (const ImportError& e) {
    return e.what();
  }
  return "(imported)";
}

TEST(GramBellhopImport, EveryConformanceEnvironmentImportsAndValidates) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kEnvDir)) {
    if (entry.path().extension() != ".env") continue;
    SCOPED_TRACE(entry.path().string());
    const auto imported = import_bellhop_env_file(entry.path());
    EXPECT_EQ(validate_environment(imported.environment), std::nullopt);
    ++count;
  }
  EXPECT_GE(count, 13);
}

TEST(GramBellhopImport, ConvertsKilometresAndAttenuationAndExpandsVectors) {
  const Environment env = import(env_text()).environment;
  EXPECT_EQ(env.frequency_hz(), 500);
  ASSERT_EQ(env.receiver_range_m_size(), 393);
  EXPECT_DOUBLE_EQ(env.receiver_range_m(0), 200.0);
  EXPECT_DOUBLE_EQ(env.receiver_range_m(392), 10000.0);
  EXPECT_NEAR(env.receiver_range_m(1), 225.0, 1e-9);
  ASSERT_EQ(env.receiver_depth_m_size(), 25);
  EXPECT_NEAR(env.receiver_depth_m(1), 6.0, 1e-12);
  EXPECT_EQ(env.bottom().kind(), Boundary::HALF_SPACE);
  // 0.8 dB/λ at 500 Hz in 1650 m/s: a f / (8.6859 c) Np/m.
  EXPECT_NEAR(env.bottom().half_space().attenuation_np_per_m(), 0.8 * 500 / (8.685889638 * 1650), 1e-12);
  EXPECT_DOUBLE_EQ(env.bottom().half_space().density_ratio(), 1.9);
  EXPECT_DOUBLE_EQ(env.box_range_m(), 10100.0);
  EXPECT_EQ(env.beam_count(), 0u);
  EXPECT_EQ(env.surface().kind(), Boundary::VACUUM);
}

TEST(GramBellhopImport, ReadsABathymetryFileThroughTheSideFileLoader) {
  SideFileLoader side = [](const std::string& ext) -> std::optional<std::string> {
    if (ext != "bty") return std::nullopt;
    return std::string("'L'\n3\n0 100\n5 90\n10 100\n");
  };
  const Environment env = import(env_text("'CVW'", "'A*' 0.0"), side).environment;
  ASSERT_EQ(env.bathymetry_size(), 3);
  EXPECT_DOUBLE_EQ(env.bathymetry(1).range_m(), 5000.0);
  EXPECT_DOUBLE_EQ(env.bathymetry(1).depth_m(), 90.0);
}

TEST(GramBellhopImport, WarnsWhenTheBathymetryDoesNotReachTheBox) {
  auto side_to = [](const std::string& last_km) {
    return SideFileLoader([last_km](const std::string&) {
      return std::optional<std::string>("'L'\n2\n0 100\n" + last_km + " 100\n");
    });
  };
  const auto short_bty = import(env_text("'CVW'", "'A*' 0.0"), side_to("10"));  // RBOX is 10.1 km
  ASSERT_EQ(short_bty.warnings.size(), 1u);
  EXPECT_NE(short_bty.warnings[0].find("extended flat"), std::string::npos) << short_bty.warnings[0];
  EXPECT_TRUE(import(env_text("'CVW'", "'A*' 0.0"), side_to("11")).warnings.empty());
}

TEST(GramBellhopImport, RefusesCurvilinearBathymetryByName) {
  SideFileLoader side = [](const std::string&) { return std::optional<std::string>("'C'\n2\n0 100\n10 100\n"); };
  const std::string message = refusal(env_text("'CVW'", "'A*' 0.0"), side);
  EXPECT_NE(message.find("curvilinear ('C')"), std::string::npos) << message;
}

TEST(GramBellhopImport, RefusesAMissingBathymetryFile) {
  const std::string message = refusal(env_text("'CVW'", "'A*' 0.0"), [](const std::string&) {
    return std::optional<std::string>();
  });
  EXPECT_NE(message.find("bathymetry file (.bty)"), std::string::npos) << message;
}

TEST(GramBellhopImport, RefusesUnsupportedOptionsNamingThem) {
  struct Case {
    std::string text, expected;
  };
  const std::vector<Case> cases = {
      {env_text("'QVW'"), "TOPOPT(1) SSP interpolation 'Q'"},
      {env_text("'AVW'"), "TOPOPT(1) SSP interpolation 'A'"},
      {env_text("'CFW'"), "TOPOPT(2) top boundary 'F'"},
      {env_text("'CVm'"), "TOPOPT(3) attenuation units 'm'"},
      {env_text("'CVWB'"), "TOPOPT(4) volume attenuation 'B'"},
      {env_text("'CVW *'"), "TOPOPT(5) altimetry '*'"},
      {env_text("'CVW'", "'G' 0.0"), "BOTOPT(1) bottom type 'G'"},
      {env_text("'CVW'", "'A' 0.0", "'CR'"), "RUNTYPE(2) beam type 'R'"},
      {env_text("'CVW'", "'A' 0.0", "'EG'"), "RUNTYPE(1) 'E'"},
      {env_text("'CVW'", "'A' 0.0", "'CG X'"), "RUNTYPE(4) source type 'X'"},
      {env_text("'CVW'", "'A' 0.0", "'CG RR3'"), "RUNTYPE(6) '3'"},
      {env_text("'CVW'", "'A' 0.0", "'CG RR2S'"), "RUNTYPE(7) beam shift 'S'"},
      {env_text("'CVW'", "'A' 0.0", "'CG*'"), "RUNTYPE(3) source beam pattern '*'"},
      {env_text("'CVW'", "'A' 0.0", "'CG'", "100 1650 400 1.9 0.8 0.0 /"), "shear speed cs"},
  };
  for (const auto& c : cases) {
    const std::string message = refusal(c.text);
    EXPECT_NE(message.find(c.expected), std::string::npos) << "expected '" << c.expected << "', got: " << message;
    EXPECT_EQ(message.rfind("test.env:", 0), 0u) << message;
  }
}

TEST(GramBellhopImport, RefusesLayeredMediaAndBadVectorsAndProfiles) {
  std::string two_media = env_text();
  two_media.replace(two_media.find("\n1\n"), 3, "\n2\n");
  EXPECT_NE(refusal(two_media).find("NMEDIA = 2"), std::string::npos);
  std::string three_values = env_text();
  three_values.replace(three_values.find("2 98 /"), 6, "2 50 98 /");
  EXPECT_NE(refusal(three_values).find("3 values given for N = 25"), std::string::npos);
  std::string decreasing = env_text();
  decreasing.replace(decreasing.find("100 1500 /"), 10, "0 1500 /\n100 1500 /");
  EXPECT_NE(refusal(decreasing).find("not greater than the previous"), std::string::npos);
  std::string not_a_number = env_text();
  not_a_number.replace(not_a_number.find("\n500\n"), 5, "\nfive\n");
  EXPECT_NE(refusal(not_a_number).find("'five' is not a number"), std::string::npos);
  EXPECT_NE(refusal("'title'\n500\n").find("the file ends before"), std::string::npos);
}

TEST(GramBellhopImport, WarnsAboutRayCentredInfluenceInsteadOfMisreadingIt) {
  const auto imported = import(env_text("'CVW'", "'A' 0.0", "'Cg'"));
  EXPECT_EQ(imported.environment.beam_shape(), HAT);
  ASSERT_EQ(imported.warnings.size(), 1u);
  EXPECT_NE(imported.warnings[0].find("ray-centred"), std::string::npos);
}

TEST(GramBellhopImport, BtyRefusesLongFormatAndNonIncreasingRanges) {
  EXPECT_THROW(import_bellhop_bty("'LL'\n2\n0 100 1600 0 1.8 0.8 0\n1 100 1600 0 1.8 0.8 0\n", "x.bty"), ImportError);
  try {
    import_bellhop_bty("'L'\n2\n1 100\n1 90\n", "x.bty");
    FAIL() << "imported";
  } catch (const ImportError& e) {
    EXPECT_NE(std::string(e.what()).find("x.bty:4: ranges must be strictly increasing"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace acomms::gram
