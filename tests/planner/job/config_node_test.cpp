// planner/job/config_node.h: the last malformed YAML a user can write (issue 18): duplicate keys,
// keys that are lists or maps, a misspelt key next to the missing one, absurd nesting.
#include "planner/job/config_node.h"

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "planner/job/job.h"
#include "tests/planner/job_error.h"

namespace windplan {
namespace {

const std::string kPipe = "mandrel: {source: pipe, pipe: {radius: 50, length: 500}}\n";

TEST(ConfigNode, DuplicateKeyNamesBothLines) {
  // yaml-cpp keeps the first value (turns: 3) without a word.
  const std::string e = test::job_load_error(kPipe + "winding:\n  turns: 3\n  turns: 0.5\n");
  EXPECT_NE(e.find("/jobs/j.yaml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("duplicate key 'winding.turns'"), std::string::npos) << e;
  EXPECT_NE(e.find("line 3"), std::string::npos) << e;
}

TEST(ConfigNode, DuplicateSectionAndDuplicateInFlowMap) {
  EXPECT_NE(test::job_load_error(kPipe + "winding: {turns: 2}\nwinding: {turns: 3}\n")
                .find("duplicate key 'winding'"),
            std::string::npos);
  const std::string e =
      test::job_load_error("mandrel: {source: pipe, pipe: {radius: 50, radius: 60, length: 5}}\n");
  EXPECT_NE(e.find("duplicate key 'mandrel.pipe.radius'"), std::string::npos) << e;
}

TEST(ConfigNode, NonScalarKeyIsAConfigErrorWithTheLine) {
  // Once escaped ConfigNode::where/finish as YAML::TypedBadConversion (exit 3).
  std::string e = test::job_load_error(kPipe + "[a]: 1\n");
  EXPECT_NE(e.find("/jobs/j.yaml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("a key is a list"), std::string::npos) << e;
  e = test::job_load_error(
      "mandrel:\n  source: pipe\n  {x: 1}: 2\n  pipe: {radius: 50, length: 500}\n");
  EXPECT_NE(e.find("/jobs/j.yaml:3"), std::string::npos) << e;
  EXPECT_NE(e.find("a key in 'mandrel' is a map"), std::string::npos) << e;
}

TEST(ConfigNode, MissingKeyNamesTheMisspeltOneBeside) {
  const std::string e =
      test::job_load_error("mandrel:\n  source: pipe\n  pipe:\n    radius: 50\n    lenght: 500\n");
  EXPECT_NE(e.find("missing required key 'mandrel.pipe.length'"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key 'mandrel.pipe.lenght' on line 5"), std::string::npos) << e;
}

TEST(ConfigNode, MissingKeyWithoutALookAlikeSaysOnlyThat) {
  const std::string e =
      test::job_load_error("mandrel: {source: pipe, pipe: {radius: 50, colour: 5}}\n");
  EXPECT_NE(e.find("missing required key 'mandrel.pipe.length'"), std::string::npos) << e;
  EXPECT_EQ(e.find("misspelling"), std::string::npos) << e;
}

TEST(ConfigNode, DeepNestingIsRefused) {
  const std::string e =
      test::job_load_error(kPipe + "x: " + std::string(100, '[') + std::string(100, ']') + "\n");
  EXPECT_NE(e.find("nested more than 64 levels"), std::string::npos) << e;
}

TEST(ConfigNode, KeysThatAreNumbersOrQuotedStringsAreStillNames) {
  // Scalar keys of any spelling are fine (and then unknown).
  const std::string e = test::job_load_error(kPipe + "\"3\": 1\n");
  EXPECT_NE(e.find("unknown key '3'"), std::string::npos) << e;
}

}  // namespace
}  // namespace windplan
