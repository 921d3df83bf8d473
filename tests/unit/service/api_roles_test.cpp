// The API's role table (service/api_roles.h): every method of both services
// has a role, so a new RPC cannot be added without deciding who may call
// it; roles are ordered; a role config with a mistake is refused naming the
// field. (Each role's calls over real mutual TLS: tests/integration/
// api_roles_test.cpp.)
#include "service/api_roles.h"

#include <google/protobuf/descriptor.h>
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "acomms/v1/acomms.grpc.pb.h"
#include "acomms/v1/gram.grpc.pb.h"

namespace acomms::service {
namespace {

// Through a message of the service's own file, so that the file is linked
// in and its descriptor registered.
std::set<std::string> methods_of(const google::protobuf::FileDescriptor* file, const std::string& service) {
  const auto* descriptor = file->pool()->FindServiceByName(service);
  EXPECT_NE(descriptor, nullptr) << service;
  std::set<std::string> names;
  for (int i = 0; descriptor && i < descriptor->method_count(); ++i) {
    names.insert("/" + service + "/" + descriptor->method(i)->name());
  }
  return names;
}

TEST(ApiRolesTest, EveryMethodOfBothServicesHasARoleAndTheTableNamesNoOther) {
  std::set<std::string> methods = methods_of(v1::Status::descriptor()->file(), "acomms.v1.Acomms");
  std::set<std::string> gram = methods_of(v1::TransmissionLossRequest::descriptor()->file(), "acomms.v1.Gram");
  methods.insert(gram.begin(), gram.end());
  ASSERT_GT(methods.size(), 20u);
  for (const std::string& method : methods) {
    EXPECT_TRUE(required_roles().count(method)) << method << " has no role in service/api_roles.cpp";
  }
  for (const auto& [method, role] : required_roles()) {
    EXPECT_TRUE(methods.count(method)) << method << " is in the table but no service has it";
  }
}

TEST(ApiRolesTest, TheIssuesCallsHaveTheirRoles) {
  const auto& table = required_roles();
  for (const char* m : {"GetStatus", "Subscribe", "Events", "ListQueued", "Track"}) {
    EXPECT_EQ(table.at(std::string("/acomms.v1.Acomms/") + m), Role::kViewer) << m;
  }
  for (const char* m : {"Submit", "Cancel", "SubmitNavigation"}) {
    EXPECT_EQ(table.at(std::string("/acomms.v1.Acomms/") + m), Role::kOperator) << m;
  }
  EXPECT_EQ(table.at("/acomms.v1.Gram/UpdateEnvironment"), Role::kOperator);
  for (const char* m : {"LoadDefinitions", "Flush", "SetCycle", "DriverSpecific"}) {
    EXPECT_EQ(table.at(std::string("/acomms.v1.Acomms/") + m), Role::kAdmin) << m;
  }
  EXPECT_LT(Role::kViewer, Role::kOperator);
  EXPECT_LT(Role::kOperator, Role::kAdmin);
}

TEST(ApiRolesTest, UnknownRoleNamesAndTwiceListedCertificatesAreRefused) {
  v1::AuthConfig config;
  config.set_unix_socket_role("root");
  try {
    ApiRoles roles(config);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "auth.unix_socket_role \"root\" is not a role (viewer, operator or admin)");
  }
  v1::AuthConfig twice;
  for (int i = 0; i < 2; ++i) {
    v1::ClientRole* client = twice.add_client();
    client->set_common_name("ops");
    client->set_role("operator");
  }
  EXPECT_THROW(ApiRoles{twice}, std::invalid_argument);
  EXPECT_EQ(role_named("viewer"), Role::kViewer);
  EXPECT_EQ(role_named("Admin"), std::nullopt);
}

}  // namespace
}  // namespace acomms::service
