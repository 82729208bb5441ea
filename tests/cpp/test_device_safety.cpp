// What a haptic device may be sent and what a device bridge's message means: the force limiter
// (magnitude, change per frame, non-finite forces never sent), the workspace around the organ,
// and the protocol's line rules (frames, comments, "end", errors with short excerpts).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "softsim/haptic/device_safety.hpp"
#include "softsim/haptic/wire_protocol.hpp"

#include "support/scenes.hpp"

using namespace softsim;
using haptic::ForceLimiter;
using haptic::WireLine;

TEST(ForceLimiter, ForcesWithinTheLimitsPassBitForBit) {
  ForceLimiter limiter({10.0, 2.0, 1.0});
  const Eigen::Vector3d a(0.3, -1.2, 0.9), b(1.1, -2.0, 1.5);
  EXPECT_EQ(limiter.limit(1, a), a);
  EXPECT_EQ(limiter.limit(2, b), b);
  EXPECT_EQ(limiter.clamped_frames(), 0);
}

TEST(ForceLimiter, MagnitudeIsClampedAlongTheSameDirection) {
  ForceLimiter limiter({5.0, 1e9, 1.0});
  const Eigen::Vector3d asked(-40592.0, 300.0, 12.0);  // a tip 1 km away
  const Eigen::Vector3d sent = limiter.limit(1, asked);
  EXPECT_NEAR(sent.norm(), 5.0, 1e-12);
  EXPECT_NEAR(sent.normalized().dot(asked.normalized()), 1.0, 1e-12);
  ASSERT_EQ(limiter.listed().size(), 1u);
  EXPECT_EQ(limiter.listed()[0].asked, asked);
  EXPECT_EQ(limiter.payload()["clamps"][0]["reasons"][0], "max_force");
}

TEST(ForceLimiter, ChangePerFrameIsLimitedAndTheLimitedForceStaysInTheBall) {
  ForceLimiter limiter({10.0, 0.5, 1.0});
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  // A step to 7e34 N (a stiff probe on its way to a failure) ramps at 0.5 N per frame to 10 N.
  for (long k = 1; k <= 40; ++k) {
    const Eigen::Vector3d sent = limiter.limit(k, Eigen::Vector3d(0, 0, 7e34));
    EXPECT_LE((sent - previous).norm(), 0.5 + 1e-12);
    EXPECT_LE(sent.norm(), 10.0 + 1e-12);
    previous = sent;
  }
  EXPECT_NEAR(previous.z(), 10.0, 1e-12);
  EXPECT_EQ(limiter.clamped_frames(), 40);
  // Letting go (an exact zero: the contact released) is never slowed down.
  EXPECT_EQ(limiter.limit(41, Eigen::Vector3d::Zero()), Eigen::Vector3d::Zero());
}

TEST(ForceLimiter, NonFiniteForcesAreNeverSentAndRestartFromZero) {
  ForceLimiter limiter({10.0, 1.0, 1.0});
  limiter.limit(1, Eigen::Vector3d(0, 0, 0.8));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(limiter.limit(2, Eigen::Vector3d(nan, 0, 1)), Eigen::Vector3d::Zero());
  EXPECT_EQ(limiter.limit(3, Eigen::Vector3d(0, std::numeric_limits<double>::infinity(), 0)), Eigen::Vector3d::Zero());
  EXPECT_EQ(limiter.non_finite_frames(), 2);
  // The next finite force rises from zero, not from the force before the failure.
  EXPECT_NEAR(limiter.limit(4, Eigen::Vector3d(0, 0, 5)).z(), 1.0, 1e-12);
  const auto p = limiter.payload();
  EXPECT_TRUE(p["clamps"][0]["asked"][0].is_null());  // NaN has no JSON number
  EXPECT_EQ(p["non_finite_frames"], 2);
}

TEST(Workspace, PositionsFarFromTheOrganAreOutside) {
  const auto mesh = test_scenes::cuboid(2, 2, 2, 0.1, 0.1, 0.05);
  const haptic::Workspace w(mesh, 1.0);
  EXPECT_TRUE(w.contains({0.05, 0.05, 0.06}));
  EXPECT_DOUBLE_EQ(w.distance({0.05, 0.05, 0.02}), 0.0);
  EXPECT_NEAR(w.distance({0.05, 0.05, 1.05}), 1.0, 1e-12);
  EXPECT_FALSE(w.contains({50, 50, 20}));  // millimetres sent as metres
  EXPECT_FALSE(w.contains({0.05, 0.05, 1000.0}));
}

TEST(WireProtocol, FramesKeepTheTimeTextAsReceived) {
  WireLine w;
  haptic::parse_wire_line("1764350000.123456789 0.01 -2e-3\t0.5\r", w);
  ASSERT_EQ(w.kind, WireLine::Kind::frame);
  EXPECT_EQ(w.t_text, "1764350000.123456789");
  EXPECT_EQ(w.position, Eigen::Vector3d(0.01, -2e-3, 0.5));
  char answer[128];
  const std::size_t n = haptic::format_force_answer(answer, sizeof answer, w.t_text, Eigen::Vector3d(0.1, 0, -1));
  EXPECT_EQ(std::string(answer, n), "1764350000.123456789 0.10000000000000001 0 -1\n");
}

TEST(WireProtocol, CommentsBlankLinesEndAndErrors) {
  WireLine w;
  for (const char* c : {"", "   ", "# a note", "  # 1 2 3 4"}) {
    haptic::parse_wire_line(c, w);
    EXPECT_EQ(w.kind, WireLine::Kind::comment) << c;
  }
  haptic::parse_wire_line(" end ", w);
  EXPECT_EQ(w.kind, WireLine::Kind::end);
  const std::pair<std::string, std::string> bad[] = {
      {std::string("\0 1 2 3", 7), "NUL byte"},
      {"0.1 0.2 0.3", "expected 4 numbers"},
      {"0.1 0.2 0.3 0.4 0.5", "got more"},
      {"0.1 0.2 nan 0.4", "finite"},
      {"0.1 0.2 1e999 0.4", "finite"},
      {"0.1 0.2x 0.3 0.4", "expected a number"},
      {"ende", "expected a number"}};
  for (const auto& [line, expect] : bad) {
    haptic::parse_wire_line(line, w);
    EXPECT_EQ(w.kind, WireLine::Kind::error) << line;
    EXPECT_NE(w.error.find(expect), std::string::npos) << w.error;
  }
}

TEST(WireProtocol, LongLinesAreRefusedWithAShortExcerpt) {
  WireLine w;
  const std::string line(100000, '7');
  haptic::parse_wire_line(line, w);
  ASSERT_EQ(w.kind, WireLine::Kind::error);
  EXPECT_NE(w.error.find("at most 512 bytes"), std::string::npos);
  EXPECT_LT(w.error.size(), 200u);
  EXPECT_EQ(haptic::excerpt(std::string(3, '\x01')), "\"\\x01\\x01\\x01\"");
  EXPECT_EQ(haptic::excerpt(std::string(50, 'a')).size(), 2 + haptic::kExcerptBytes + 3);
}
