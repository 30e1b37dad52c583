#include "common/json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace duet {
namespace {

TEST(ParseJson, ReadsBackWhatDumpWrites) {
  Json j = Json::object();
  j["scene"] = "collapse \"bui\"\n\tline";
  j["spacing"] = 0.0025;
  j["steps"] = 70711L;
  j["status"] = "completed";
  j["failure"] = Json();
  j["ok"] = true;
  j["nan_becomes_null"] = std::nan("");
  j["series"] = Json::array({1.5, -2.25e-7, 3e300});
  j["nested"]["deep"]["value"] = -1.0;
  for (int indent : {0, 2}) {
    const Json back = parse_json(j.dump(indent));
    EXPECT_EQ(back.dump(), j.dump()) << indent;
    EXPECT_EQ(back.find("scene")->string(), "collapse \"bui\"\n\tline");
    EXPECT_DOUBLE_EQ(back.find("spacing")->number(), 0.0025);
    EXPECT_TRUE(back.find("failure")->is_null());
    EXPECT_TRUE(back.find("ok")->boolean());
    EXPECT_EQ(back.find("series")->elements().size(), 3u);
    EXPECT_DOUBLE_EQ(back.find("series")->elements()[2].number(), 3e300);
  }
}

TEST(ParseJson, UnicodeEscapes) {
  EXPECT_EQ(parse_json(R"("\u00e9\u6f22\ud83d\ude00")").string(), "\u00e9\u6f22\U0001F600");
}

TEST(ParseJson, RefusesBrokenTextNamingTheOffset) {
  for (const char* bad :
       {"", "{", "{\"a\" 1}", "[1, 2", "tru", "\"open", "{\"a\": 1,}", "1 2", "[01x]", "\"\\q\""}) {
    try {
      parse_json(bad);
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("JSON at offset"), std::string::npos) << e.what();
    }
  }
  // Deep nesting is refused, not a stack overflow.
  EXPECT_THROW(parse_json(std::string(100000, '[')), std::runtime_error);
}

}  // namespace
}  // namespace duet
