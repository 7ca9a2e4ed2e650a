#include "tightfit/body/bvh.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>

#include "tightfit/common/error.hpp"

namespace tightfit::bvh_test {

const std::filesystem::path kBvhData = std::filesystem::path(TIGHTFIT_DATA_DIR) / "rig";

/// A one-joint file: ROOT "hips" with `channels` (a CHANNELS line's tail) and `motion`
/// (the text after "MOTION\n").
std::string bvh_one_joint(const std::string& channels, const std::string& motion) {
  return "HIERARCHY\nROOT hips\n{\n\tOFFSET 1 2 3\n\tCHANNELS " + channels +
         "\n\tEnd Site\n\t{\n\t\tOFFSET 0 1 0\n\t}\n}\nMOTION\n" + motion;
}

/// A valid two-joint file with 6 + 3 channels and two frames.
std::string bvh_two_joints() {
  return "HIERARCHY\n"
         "ROOT hips\n"
         "{\n"
         "  OFFSET 0 0 0\n"
         "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
         "  JOINT chest\n"
         "  {\n"
         "    OFFSET 0 5.5 -1\n"
         "    CHANNELS 3 Zrotation Xrotation Yrotation\n"
         "    End Site\n"
         "    {\n"
         "      OFFSET 0 2 0\n"
         "    }\n"
         "  }\n"
         "}\n"
         "MOTION\n"
         "Frames: 2\n"
         "Frame Time: 0.05\n"
         "1 2 3 10 20 30 40 50 60\n"
         "4 5 6 -10 -20 -30 -40 -50 -60\n";
}

/// The InputError message of parsing `text` as "hostile.bvh"; fails the test if it parses.
std::string bvh_error(const std::string& text) {
  try {
    parse_bvh(text, "hostile.bvh");
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "parsed without an error:\n" << text.substr(0, 400);
  return "";
}

/// Expects an InputError naming the source and a line, and containing `words`.
void bvh_expect_error(const std::string& text, const std::string& words) {
  const std::string message = bvh_error(text);
  EXPECT_NE(message.find("hostile.bvh: line "), std::string::npos) << message;
  EXPECT_NE(message.find(words), std::string::npos) << message;
}

Mat3 bvh_axis(const Vec3& axis, double degrees) {
  return Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis).toRotationMatrix();
}

TEST(Bvh, ReadsMakeHumansBenchmarkPose) {
  const BvhMotion motion = read_bvh(kBvhData / "benchmark.bvh");
  // The ROOT and its 162 JOINT blocks (End Sites are not joints).
  EXPECT_EQ(motion.joints.size(), 163u);
  EXPECT_EQ(motion.num_frames(), 1);
  EXPECT_NEAR(motion.frame_time, 0.041667, 1e-12);
  ASSERT_FALSE(motion.joints.empty());
  EXPECT_EQ(motion.joints[0].name, "root");
  EXPECT_EQ(motion.joints[0].parent, -1);
  EXPECT_EQ(motion.joints[0].channels.size(), 6u);
  EXPECT_NEAR(motion.joints[0].offset.z(), 6.314334, 1e-12);  // z-up, decimetres
  int channels = 0;
  for (std::size_t i = 0; i < motion.joints.size(); ++i) {
    const BvhJoint& joint = motion.joints[i];
    if (i > 0) {
      EXPECT_GE(joint.parent, 0) << joint.name;
      EXPECT_LT(joint.parent, static_cast<int>(i)) << joint.name;
    }
    EXPECT_EQ(joint.first_channel, channels) << joint.name;
    channels += static_cast<int>(joint.channels.size());
  }
  EXPECT_EQ(motion.num_channels, channels);
  EXPECT_EQ(motion.frames.cols(), 891);
  const int shin = motion.find("lowerleg01.L");
  ASSERT_GE(shin, 0);
  EXPECT_EQ(motion.joints[static_cast<std::size_t>(shin)].name, "lowerleg01.L");
  EXPECT_EQ(motion.find("no such bone"), -1);
  EXPECT_EQ(motion.source, (kBvhData / "benchmark.bvh").string());
}

TEST(Bvh, ReadsMakeHumansTPose) {
  const BvhMotion motion = read_bvh(kBvhData / "tpose.bvh");
  EXPECT_EQ(motion.num_frames(), 1);
  EXPECT_GT(motion.joints.size(), 100u);
  EXPECT_EQ(motion.joints[0].parent, -1);
  EXPECT_GE(motion.find("lowerleg01.L"), 0);
  EXPECT_EQ(motion.frames.cols(), motion.num_channels);
  EXPECT_TRUE(motion.frames.allFinite());
}

TEST(Bvh, ReadsHierarchyChannelsAndFrames) {
  const BvhMotion motion = parse_bvh(bvh_two_joints(), "two.bvh");
  ASSERT_EQ(motion.joints.size(), 2u);
  EXPECT_EQ(motion.joints[1].name, "chest");
  EXPECT_EQ(motion.joints[1].parent, 0);
  EXPECT_EQ(motion.joints[1].offset, Vec3(0, 5.5, -1));
  EXPECT_EQ(motion.joints[1].first_channel, 6);
  EXPECT_EQ(motion.joints[1].channels,
            (std::vector<BvhChannel>{BvhChannel::kZrotation, BvhChannel::kXrotation,
                                     BvhChannel::kYrotation}));
  EXPECT_EQ(motion.num_channels, 9);
  EXPECT_DOUBLE_EQ(motion.frame_time, 0.05);
  ASSERT_EQ(motion.frames.rows(), 2);
  ASSERT_EQ(motion.frames.cols(), 9);
  EXPECT_EQ(motion.frames(0, 0), 1.0);
  EXPECT_EQ(motion.frames(1, 8), -60.0);
  EXPECT_EQ(motion.source, "two.bvh");
}

TEST(Bvh, LocalRotationIsTheProductOfTheChannelsInFileOrder) {
  const BvhMotion motion = parse_bvh(
      bvh_one_joint("3 Zrotation Xrotation Yrotation", "Frames: 1\nFrame Time: 0.1\n30 45 60\n"),
      "one.bvh");
  const Mat3 expected =
      bvh_axis(Vec3::UnitZ(), 30) * bvh_axis(Vec3::UnitX(), 45) * bvh_axis(Vec3::UnitY(), 60);
  const Mat3 r = motion.local_rotation(0, 0);
  EXPECT_LT((r - expected).norm(), 1e-12) << r;
  EXPECT_LT((r.transpose() * r - Mat3::Identity()).norm(), 1e-12);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  // Right-handed: +90° about z takes x to y.
  const BvhMotion quarter =
      parse_bvh(bvh_one_joint("1 Zrotation", "Frames: 1\nFrame Time: 0.1\n90\n"), "quarter.bvh");
  EXPECT_LT((quarter.local_rotation(0, 0) * Vec3::UnitX() - Vec3::UnitY()).norm(), 1e-12);
}

TEST(Bvh, LocalRotationSkipsPositionChannelsAndChecksIndices) {
  const BvhMotion motion = parse_bvh(bvh_two_joints(), "two.bvh");
  const Mat3 root =
      bvh_axis(Vec3::UnitZ(), -10) * bvh_axis(Vec3::UnitX(), -20) * bvh_axis(Vec3::UnitY(), -30);
  EXPECT_LT((motion.local_rotation(0, 1) - root).norm(), 1e-12);
  const Mat3 chest =
      bvh_axis(Vec3::UnitZ(), 40) * bvh_axis(Vec3::UnitX(), 50) * bvh_axis(Vec3::UnitY(), 60);
  EXPECT_LT((motion.local_rotation(1, 0) - chest).norm(), 1e-12);
  const BvhMotion still = parse_bvh(
      bvh_one_joint("3 Xposition Yposition Zposition", "Frames: 1\nFrame Time: 0.1\n1 2 3\n"),
      "still.bvh");
  EXPECT_EQ(still.local_rotation(0, 0), Mat3::Identity());
  EXPECT_THROW(motion.local_rotation(2, 0), std::out_of_range);
  EXPECT_THROW(motion.local_rotation(-1, 0), std::out_of_range);
  EXPECT_THROW(motion.local_rotation(0, 2), std::out_of_range);
  EXPECT_THROW(motion.local_rotation(0, -1), std::out_of_range);
}

TEST(Bvh, AcceptsCrlfAnyChannelCaseAndValuesSplitOverLines) {
  std::string crlf;
  for (const char c : bvh_two_joints())
    crlf += (c == '\n') ? std::string("\r\n") : std::string(1, c);
  const BvhMotion a = parse_bvh(crlf, "crlf.bvh");
  const BvhMotion b = parse_bvh(bvh_two_joints(), "lf.bvh");
  EXPECT_EQ(a.frames, b.frames);
  EXPECT_EQ(a.joints.size(), 2u);

  const BvhMotion split =
      parse_bvh(bvh_one_joint("3 zROTATION xrotation YRotation",
                              "Frames: 2\nFrame Time: 0.1\n1\n2 3 4\n\n  5\t6\n"),
                "split.bvh");
  ASSERT_EQ(split.frames.rows(), 2);
  EXPECT_EQ(split.frames(0, 0), 1.0);
  EXPECT_EQ(split.frames(1, 0), 4.0);
  EXPECT_EQ(split.frames(1, 2), 6.0);
  EXPECT_EQ(split.joints[0].channels[1], BvhChannel::kXrotation);

  const BvhMotion empty =
      parse_bvh(bvh_one_joint("0", "Frames: 0\nFrame Time: 0.1\n"), "empty.bvh");
  EXPECT_EQ(empty.num_frames(), 0);
  EXPECT_EQ(empty.num_channels, 0);
}

TEST(Bvh, ReportsMalformedHierarchiesWithTheirLine) {
  const std::string motion = "Frames: 1\nFrame Time: 0.1\n0 0 0\n";
  bvh_expect_error(bvh_one_joint("3 Zrotation Xrotation Wrotation", motion), "unknown channel");
  bvh_expect_error(bvh_one_joint("3 Zrotation Xrotation Zrotation", motion), "listed twice");
  bvh_expect_error(bvh_one_joint("3 Zrotation Xrotation", motion),
                   "CHANNELS 3 but 2 channel names");
  bvh_expect_error(bvh_one_joint("3 Zrotation\nXrotation Yrotation", motion), "CHANNELS 3 but 1");
  bvh_expect_error(bvh_one_joint("7 Zrotation Xrotation Yrotation", motion), "0..6");
  bvh_expect_error(
      "HIERARCHY\nROOT hips\n{\n\tOFFSET 0 nan 0\n}\nMOTION\nFrames: 0\nFrame Time: 1\n",
      "not finite");
  bvh_expect_error(
      "HIERARCHY\nROOT hips\n{\n\tOFFSET 0 inf 0\n}\nMOTION\nFrames: 0\nFrame Time: 1\n",
      "not finite");
  bvh_expect_error("HIERARCHY\nROOT hips\n{\n\tOFFSET 0 0\n}\nMOTION\nFrames: 0\nFrame Time: 1\n",
                   "OFFSET needs 3 numbers, found 2");
  bvh_expect_error(
      "HIERARCHY\nROOT hips\n{\n\tOFFSET 0 0 0 0\n}\nMOTION\nFrames: 0\nFrame Time: 1\n",
      "found 4");
  bvh_expect_error(
      "HIERARCHY\nROOT hips\n{\n\tOFFSET 0 0 0\n\tROTATE 1\n}\nMOTION\nFrames: 0\nFrame Time: 1\n",
      "unknown keyword \"ROTATE\"");
  bvh_expect_error("HIERARCHY\nROOT\n{\n\tOFFSET 0 0 0\n}\nMOTION\nFrames: 0\nFrame Time: 1\n",
                   "without a name");
  bvh_expect_error(
      "HIERARCHY\nROOT hips\n{\n\tOFFSET 0 0 0\n\tJOINT\n\t{\n\t\tOFFSET 0 0 0\n\t}\n}\n"
      "MOTION\nFrames: 0\nFrame Time: 1\n",
      "JOINT without a name");
  bvh_expect_error(
      "HIERARCHY\nROOT hips\n{\n\tOFFSET 0 0 0\n\tJOINT hips\n\t{\n\t\tOFFSET 0 0 0\n\t}\n}\n"
      "MOTION\nFrames: 0\nFrame Time: 1\n",
      "duplicate joint name \"hips\"");
  bvh_expect_error(
      "HIERARCHY\nROOT a\n{\n\tOFFSET 0 0 0\n}\nROOT b\n{\n\tOFFSET 0 0 0\n}\n"
      "MOTION\nFrames: 0\nFrame Time: 1\n",
      "second ROOT");
  bvh_expect_error("HIERARCHY\nROOT hips\n\tOFFSET 0 0 0\n}\nMOTION\nFrames: 0\nFrame Time: 1\n",
                   "expected '{' after ROOT \"hips\"");
  bvh_expect_error("HIERARCHY\nROOT hips\n{\n\tOFFSET 0 0 0\nMOTION\nFrames: 0\nFrame Time: 1\n",
                   "MOTION inside joint \"hips\": missing '}'");
  bvh_expect_error("HIERARCHY\nROOT hips\n{\n\tOFFSET 0 0 0\n", "missing '}' of joint \"hips\"");
  bvh_expect_error("HIERARCHY\nROOT hips\n{\n\tOFFSET 0 0 0\n}\n", "no MOTION section");
  bvh_expect_error("HIERARCHY\nMOTION\nFrames: 0\nFrame Time: 1\n", "empty hierarchy");
  bvh_expect_error("HIERARCHY\n", "empty hierarchy");
  bvh_expect_error("", "expected HIERARCHY");
  bvh_expect_error("\x01\xff garbage", "expected HIERARCHY, found \"??\"");
}

TEST(Bvh, ReportsMalformedMotionWithTheirLine) {
  const std::string channels = "3 Zrotation Xrotation Yrotation";
  bvh_expect_error(bvh_one_joint(channels, "Frames: -1\nFrame Time: 0.1\n"), "negative");
  bvh_expect_error(bvh_one_joint(channels, "Frames: 1.5\nFrame Time: 0.1\n0 0 0\n"),
                   "not an integer");
  bvh_expect_error(bvh_one_joint(channels, "Frames: many\nFrame Time: 0.1\n0 0 0\n"),
                   "not an integer");
  bvh_expect_error(bvh_one_joint(channels, "Frames: 99999999999\nFrame Time: 0.1\n"), "too many");
  bvh_expect_error(bvh_one_joint(channels, "Frames: 1\nFrame Time: 0\n0 0 0\n"), "must be > 0");
  bvh_expect_error(bvh_one_joint(channels, "Frames: 1\nFrame Time: -0.1\n0 0 0\n"), "must be > 0");
  bvh_expect_error(bvh_one_joint(channels, "Frames: 1\nFrame Time: nan\n0 0 0\n"), "not finite");
  bvh_expect_error(bvh_one_joint(channels, "Frames: 1\nFrame Time: inf\n0 0 0\n"), "not finite");
  bvh_expect_error(bvh_one_joint(channels, "Frames: 1\n0 0 0\n"), "expected \"Frame Time:\"");
  bvh_expect_error(bvh_one_joint(channels, "Frame Time: 0.1\n0 0 0\n"), "expected \"Frames:\"");
  bvh_expect_error(bvh_one_joint(channels, "Frames: 2\nFrame Time: 0.1\n0 0 0\n0 0 0 0\n"),
                   "extra data");
  bvh_expect_error(bvh_one_joint(channels, "Frames: 2\nFrame Time: 0.1\n0 0 0\n0 nan 0\n"),
                   "frame 2: \"nan\" is not finite");
  bvh_expect_error(bvh_one_joint(channels, "Frames: 1\nFrame Time: 0.1\n0 x 0\n"),
                   "\"x\" is not a number");
  // Truncated: the first check (the file cannot hold them) and the one while reading.
  bvh_expect_error(bvh_one_joint(channels, "Frames: 3\nFrame Time: 0.1\n0 0 0\n0 0\n"),
                   "expected 9 values (3 frames x 3 channels), found 5");
  bvh_expect_error(
      bvh_one_joint(channels, "Frames: 3\nFrame Time: 0.1\n0 0 0\n0 0                   \n"),
      "expected 9 values (3 frames x 3 channels), found 5");
  const std::string line =
      bvh_error(bvh_one_joint(channels, "Frames: 3\nFrame Time: 0.1\n0 0 0\n0 0\n"));
  EXPECT_NE(line.find("line 12: "), std::string::npos) << line;  // Frames: 3
}

TEST(Bvh, AHugeFrameCountFailsWithoutAllocating) {
  std::string joints;
  std::string closes;
  for (int i = 0; i < 33; ++i) {
    joints += "JOINT j" + std::to_string(i) +
              "\n{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n";
    closes += "}\n";
  }
  const std::string text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 0\n" + joints + closes +
                           "}\nMOTION\nFrames: 1000000000\nFrame Time: 0.1\n0 0 0 0\n";
  const auto start = std::chrono::steady_clock::now();
  bvh_expect_error(text, "expected 99000000000 values (1000000000 frames x 99 channels), found 4");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
}

TEST(Bvh, DeepNestingFailsWithoutRecursion) {
  std::string text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\n";
  text.reserve(2'000'000);
  for (int i = 0; i < 100000; ++i) text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 0 0\n";
  for (int i = 0; i < 100000; ++i) text += "}\n";
  text += "}\nMOTION\nFrames: 0\nFrame Time: 0.1\n";
  bvh_expect_error(text, "nested deeper than 1000");
  // 1000 blocks (ROOT, 998 joints, an End Site) are still fine.
  std::string ok = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\n";
  for (int i = 0; i < 998; ++i) ok += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 0 0\n";
  ok += "End Site\n{\nOFFSET 0 0 0\n}\n";
  for (int i = 0; i < 999; ++i) ok += "}\n";
  ok += "MOTION\nFrames: 0\nFrame Time: 0.1\n";
  const BvhMotion deep = parse_bvh(ok, "deep.bvh");
  EXPECT_EQ(deep.joints.size(), 999u);
  EXPECT_EQ(deep.joints.back().parent, 997);
}

TEST(Bvh, ReadBvhNamesAMissingFile) {
  try {
    read_bvh(kBvhData / "no_such_file.bvh");
    ADD_FAILURE() << "read a missing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_file.bvh"), std::string::npos) << e.what();
  }
}

}  // namespace tightfit::bvh_test
