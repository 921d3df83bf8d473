// A node's links from its config (core/node_links.h, and the loader's
// checks of them): the old single driver/mac form is one link "default";
// several `link` blocks each keep their own driver and MAC and share one
// modem id; mixing the forms, unnamed or twice-named links, ids that
// disagree and routes naming no link are config errors at their place.

#include "core/node_links.h"

#include <gtest/gtest.h>

#include "core/config_error.h"
#include "core/config_loader.h"

namespace acomms::core {
namespace {

ConfigError parse_error(const std::string& text) {
  try {
    parse_config(text, "test.conf");
  } catch (const ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "no ConfigError for:\n" << text;
  return ConfigError("", 0, 0, "", "");
}

TEST(NodeLinks, SingleDriverAndMacAreOneLinkNamedDefault) {
  v1::Config config = parse_config("driver { name: \"udp\" modem_id: 4 }\nmac { name: \"fixed\" }\n", "t");
  std::vector<v1::LinkConfig> links = node_links(config);
  ASSERT_EQ(links.size(), 1u);
  EXPECT_EQ(links[0].name(), "default");
  EXPECT_EQ(links[0].driver().name(), "udp");
  EXPECT_EQ(links[0].mac().name(), "fixed");
  EXPECT_EQ(node_id(config), 4);
  EXPECT_EQ(config.link_size(), 0) << "the old form is kept as written";
}

TEST(NodeLinks, SeveralLinksKeepTheirOwnDriverAndMacAndShareTheId) {
  v1::Config config = parse_config(
      "link { name: \"acoustic\" driver { name: \"sim\" modem_id: 3 } mac { name: \"fixed\" } }\n"
      "link { name: \"tether\" driver { name: \"udp\" } cost: 0.25 enabled: false }\n",
      "t");
  std::vector<v1::LinkConfig> links = node_links(config);
  ASSERT_EQ(links.size(), 2u);
  EXPECT_EQ(links[0].name(), "acoustic");
  EXPECT_EQ(links[1].driver().name(), "udp");
  EXPECT_EQ(links[1].mac().name(), "none") << "a link's MAC defaults as the single form's";
  EXPECT_EQ(links[1].driver().modem_id(), 3u) << "an unset id takes the node's";
  EXPECT_DOUBLE_EQ(links[1].cost(), 0.25);
  EXPECT_FALSE(links[1].enabled());
  EXPECT_EQ(node_id(config), 3);
  EXPECT_FALSE(config.has_driver()) << "no top-level driver is made up";
}

TEST(NodeLinks, NoIdAnywhereIsOne) {
  v1::Config config = parse_config("link { name: \"a\" } link { name: \"b\" }", "t");
  EXPECT_EQ(node_id(config), 1);
  EXPECT_EQ(config.link(1).driver().modem_id(), 1u);
}

TEST(NodeLinks, MixingTheFormsIsAnErrorAtTheTopLevelBlock) {
  ConfigError e = parse_error("link { name: \"a\" }\ndriver { name: \"sim\" }\n");
  EXPECT_EQ(e.field(), "driver");
  EXPECT_EQ(e.line(), 2);
  EXPECT_NE(e.problem().find("not both"), std::string::npos) << e.problem();
}

TEST(NodeLinks, UnnamedDuplicateAndBadNamesAreLocated) {
  ConfigError unnamed = parse_error("link { name: \"a\" }\nlink { driver { name: \"sim\" } }\n");
  EXPECT_EQ(unnamed.field(), "link.name");
  EXPECT_NE(unnamed.problem().find("needs a name"), std::string::npos) << unnamed.problem();

  ConfigError twice = parse_error("link { name: \"a\" }\nlink {\n  name: \"a\"\n}\n");
  EXPECT_EQ(twice.field(), "link.name");
  EXPECT_EQ(twice.line(), 3) << "the second link's name";
  EXPECT_NE(twice.problem().find("\"a\" names two links"), std::string::npos) << twice.problem();

  ConfigError bad = parse_error("link { name: \"Sat Link\" }\n");
  EXPECT_NE(bad.problem().find("not a link name"), std::string::npos) << bad.problem();
}

TEST(NodeLinks, ModemIdsThatDisagreeNameBothLinks) {
  ConfigError e = parse_error(
      "link { name: \"acoustic\" driver { modem_id: 3 } }\nlink { name: \"sat\" driver {\n  modem_id: 4 } }\n");
  EXPECT_EQ(e.field(), "link.driver.modem_id");
  EXPECT_EQ(e.line(), 3);
  EXPECT_NE(e.problem().find("link \"sat\" has modem_id 4 but link \"acoustic\" has 3"), std::string::npos)
      << e.problem();
}

TEST(NodeLinks, RouteNamingNoLinkIsAnError) {
  ConfigError e = parse_error(
      "link { name: \"acoustic\" }\nqueue { type { type: \"x.S\" route { link: \"acoustic\" link: \"iridum\" } } }\n");
  EXPECT_NE(e.problem().find("\"iridum\" is not one of this node's links (\"acoustic\")"), std::string::npos)
      << e.problem();
  // The single form's link is "default".
  EXPECT_NO_THROW(parse_config("queue { route { link: \"default\" } }", "t"));
  ConfigError cost = parse_error("link { name: \"a\" cost: -1 }");
  EXPECT_EQ(cost.field(), "link.cost");
}

TEST(NodeLinks, ProgrammaticConfigIsCheckedToo) {
  v1::Config config;
  config.add_link()->set_name("a");
  config.add_link()->set_name("a");
  EXPECT_THROW(node_links(config), std::invalid_argument);
}

}  // namespace
}  // namespace acomms::core
