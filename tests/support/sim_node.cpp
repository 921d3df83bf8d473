#include "sim_node.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include "mac/mac_factory.h"
#include "submit_now.h"

namespace acomms::testing {

SimNode::SimNode(const SimNodeSetup& setup, core::SimulatedScheduler& scheduler,
                 std::shared_ptr<drivers::SimChannel> channel, link::LinkController::Deliver deliver) {
  codec.load(setup.proto);
  v1::QueueConfig queue_config;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(setup.queue_config, &queue_config))
      << setup.queue_config;
  queues = std::make_unique<queue::QueueManager>(codec, queue_config, setup.id, scheduler.clock(), journal);

  driver_config.set_name("sim");
  driver_config.set_modem_id(static_cast<uint32_t>(setup.id));
  driver_config.mutable_sim()->mutable_position()->set_x(setup.x);
  if (setup.configure_driver) setup.configure_driver(driver_config);
  driver = std::make_unique<drivers::SimDriver>(driver_config, scheduler, std::move(channel));
  if (setup.wrap_driver) wrapper = setup.wrap_driver(*driver);

  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(setup.mac_config, &mac_config)) << setup.mac_config;
  mac = mac::make_mac(mac_config, setup.id, scheduler);
  link::LinkOptions options;
  if (setup.link_options_from_mac) options = link::LinkOptions::from_config(mac_config, scheduler.clock());
  link = std::make_unique<link::LinkController>(setup.id, *queues, *mac, wrapper ? *wrapper : *driver,
                                                std::move(deliver), options);
}

void SimNode::submit(const std::string& type, const std::string& text) {
  auto m = codec.new_message(type);
  // Partial: the submit fills unset role fields (the source, the time).
  google::protobuf::TextFormat::Parser parser;
  parser.AllowPartialMessage(true);
  EXPECT_TRUE(parser.ParseFromString(text, m.get())) << text;
  queue::SubmitResult result = submit_now(*queues, *m);
  EXPECT_TRUE(result.ok()) << result.text;
}

}  // namespace acomms::testing
