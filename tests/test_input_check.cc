// InputCheck: every number a reader brought in is either repaired with a warning that names it, or refused
// with one line naming the file, the object and the value.
#include <OpenMeshSkinned/IO/InputCheck.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace OpenMeshSkinned;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

Skeleton two_joints() {
  Skeleton s;
  s.joints.resize(2);
  s.joints[0].name = "hips";
  s.joints[1].name = "knee";
  s.joints[1].parent = 0;
  return s;
}

// A clip moving the knee: translations and rotations at 0, 0.5 and 1 s.
Clip walk() {
  Clip c;
  c.name = "walk";
  c.duration = 1.0;
  Channel ch;
  ch.joint = 1;
  ch.translation_times = {0.0, 0.5, 1.0};
  ch.translations = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 2, 0)};
  ch.rotation_times = {0.0, 0.5, 1.0};
  ch.rotations.assign(3, Eigen::Quaterniond::Identity());
  c.channels.push_back(ch);
  return c;
}

std::string refusal(Clip clip, size_t targets = 0) {
  std::vector<std::string> warnings;
  try {
    check_clip(clip, two_joints(), targets, "in.x", warnings);
  } catch (const IOError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(InputCheck, AGoodClipPassesUnchangedAndWithoutWarnings) {
  Clip c = walk();
  std::vector<std::string> warnings;
  check_clip(c, two_joints(), 0, "in.x", warnings);
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(c.channels[0].translation_times, (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(c.channels[0].translations[2], Eigen::Vector3d(0, 2, 0));
  EXPECT_EQ(c.duration, 1.0);
}

TEST(InputCheck, NonFiniteKeysAreRefusedNamingClipJointKeyAndValue) {
  Clip c = walk();
  c.channels[0].translations[1].y() = kNaN;
  EXPECT_EQ(refusal(c), "in.x: clip \"walk\": joint \"knee\": translation key 1 has the non-finite value nan");
  c = walk();
  c.channels[0].rotation_times[2] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(refusal(c), "in.x: clip \"walk\": joint \"knee\": rotation key 2 has the time inf");
  c = walk();
  c.channels[0].rotation_times[2] = 1e39;  // inf once written as float seconds
  EXPECT_EQ(refusal(c), "in.x: clip \"walk\": joint \"knee\": rotation key 2 has the time 1e+39");
  c = walk();
  c.channels[0].translations[0].x() = 1e39;  // written as float: it would become inf in the file
  EXPECT_EQ(refusal(c),
            "in.x: clip \"walk\": joint \"knee\": translation key 0 has the value 1e+39, beyond float range");
}

TEST(InputCheck, AZeroQuaternionIsRefusedAndOthersRenormalised) {
  Clip c = walk();
  c.channels[0].rotations[1] = Eigen::Quaterniond(0, 0, 0, 0);
  EXPECT_EQ(refusal(c),
            "in.x: clip \"walk\": joint \"knee\": rotation key 1 has a rotation of length 0, no quaternion");
  c = walk();
  c.channels[0].rotations[1] = Eigen::Quaterniond(2, 0, 0, 0);
  std::vector<std::string> warnings;
  check_clip(c, two_joints(), 0, "in.x", warnings);
  EXPECT_DOUBLE_EQ(c.channels[0].rotations[1].norm(), 1.0);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "clip \"walk\": 1 rotation keys were not unit quaternions: renormalised");
}

TEST(InputCheck, KeysEqualInFloatSecondsAreMergedKeepingTheLater) {
  // Two keys 1e-9 s apart are distinct doubles but one float: glTF's validator calls the pair non-increasing.
  Clip c = walk();
  c.channels[0].translation_times = {0.0, 0.5, 0.5 + 1e-9, 1.0};
  c.channels[0].translations = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 7, 0),
                                Eigen::Vector3d(0, 2, 0)};
  std::vector<std::string> warnings;
  check_clip(c, two_joints(), 0, "in.x", warnings);
  const Channel& ch = c.channels[0];
  ASSERT_EQ(ch.translation_times.size(), 3u);
  for (size_t k = 1; k < ch.translation_times.size(); ++k)
    EXPECT_LT(float(ch.translation_times[k - 1]), float(ch.translation_times[k]));
  EXPECT_EQ(ch.translations[1], Eigen::Vector3d(0, 7, 0));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "clip \"walk\": 1 keys fell on the time of the key before them once written as float "
            "seconds: merged (the later kept)");
}

TEST(InputCheck, KeysOutOfOrderAreSortedWithTheirValues) {
  Clip c = walk();
  c.channels[0].translation_times = {0.5, 0.0, 1.0};
  std::vector<std::string> warnings;
  check_clip(c, two_joints(), 0, "in.x", warnings);
  EXPECT_EQ(c.channels[0].translation_times, (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(c.channels[0].translations[0], Eigen::Vector3d(0, 1, 0));  // the value moved with its time
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "clip \"walk\": 1 key lists out of time order: sorted");
}

TEST(InputCheck, AClipStartingBeforeZeroIsShiftedAndItsDurationMended) {
  Clip c = walk();
  for (double& t : c.channels[0].rotation_times) t -= 2.0;  // -2, -1.5, -1
  c.duration = kNaN;
  std::vector<std::string> warnings;
  check_clip(c, two_joints(), 0, "in.x", warnings);
  EXPECT_EQ(c.channels[0].rotation_times, (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(c.channels[0].translation_times, (std::vector<double>{2.0, 2.5, 3.0}));
  EXPECT_EQ(c.duration, 3.0);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0], "clip \"walk\": its keys start at -2 s: shifted to start at 0");
  EXPECT_EQ(warnings[1], "clip \"walk\": its duration nan is set to its last key, 3 s");
}

TEST(InputCheck, ChannelsOfMissingJointsOrTargetsAndBadMorphWeightsAreRefused) {
  Clip c = walk();
  c.channels[0].joint = 7;
  EXPECT_EQ(refusal(c), "in.x: clip \"walk\": a channel moves joint 7 of 2");
  c = walk();
  MorphChannel mc;
  mc.target = 0;
  mc.times = {0.0, 1.0};
  mc.weights = {0.0, kNaN};
  c.morph_channels.push_back(mc);
  EXPECT_EQ(refusal(c, 1), "in.x: clip \"walk\": morph target 0 weight key 1 has the non-finite value nan");
  EXPECT_EQ(refusal(c, 0), "in.x: clip \"walk\": a channel moves morph target 0 of 0");
  c = walk();
  c.channels[0].translations.pop_back();
  EXPECT_EQ(refusal(c), "in.x: clip \"walk\": joint \"knee\": translation has 3 key times but 2 values");
}

TEST(InputCheck, SkeletonTransformsMustBeFiniteInvertibleAndAffine) {
  auto refused = [](const Skeleton& s) -> std::string {
    try {
      check_skeleton(s, "in.fbx");
    } catch (const IOError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_EQ(refused(two_joints()), "accepted");
  Skeleton s = two_joints();
  s.joints[1].rest_local(0, 3) = kNaN;
  EXPECT_EQ(refused(s), "in.fbx: joint \"knee\": its rest transform has the non-finite value nan");
  s = two_joints();
  s.joints[0].rest_local.topLeftCorner<3, 3>() *= 0.0;
  EXPECT_EQ(refused(s), "in.fbx: joint \"hips\": its rest transform is not invertible (a zero scale)");
  s = two_joints();
  s.joints[1].inverse_bind(1, 1) = std::numeric_limits<double>::infinity();
  EXPECT_EQ(refused(s), "in.fbx: joint \"knee\": its inverse bind matrix has the non-finite value inf");
  s = two_joints();
  s.joints[1].inverse_bind(3, 0) = 0.5;
  EXPECT_EQ(refused(s), "in.fbx: joint \"knee\": its inverse bind matrix is not affine (its last row is not 0 0 0 1)");
}

TEST(InputCheck, NamesBecomePrintableUtf8) {
  SkinnedMesh mesh;
  add_skin(mesh);
  skeleton(mesh) = two_joints();
  skeleton(mesh).joints[0].name = "hi\xff\x01ps";
  clips(mesh).push_back(walk());
  std::vector<std::string> warnings;
  check_input(mesh, "in.x", warnings);
  EXPECT_EQ(skeleton(mesh).joints[0].name, "hi??ps");
  EXPECT_EQ(skeleton(mesh).joints[1].name, "knee");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "1 names were not printable UTF-8: their other bytes became '?'");
}
