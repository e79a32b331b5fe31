// Texts that name settings: the library spells a name as results do, the
// command line as an option, and nothing else in the text is touched.
#include <gtest/gtest.h>

#include <string>

#include "base/errors.h"

namespace crowdprof {
namespace {

std::string as_option(std::string_view name) {
  std::string option = "--" + std::string(name);
  for (char& c : option)
    if (c == '_') c = '-';
  return option;
}

TEST(SettingText, NamesAreSpelledByWhoeverSaysThem) {
  SettingText text("{share_quantum} snaps times: it needs {share} on");
  EXPECT_EQ(text.str(), "share_quantum snaps times: it needs share on");
  EXPECT_EQ(text.str(as_option), "--share-quantum snaps times: it needs --share on");
}

TEST(SettingText, BracesThatAreNotANameStayText) {
  EXPECT_EQ(SettingText("a {Name} and {two words} and {} and {x").str(as_option),
            "a {Name} and {two words} and {} and {x");
  EXPECT_EQ(SettingText("{{backend}}").str(as_option), "{--backend}");
  EXPECT_TRUE(SettingText().empty());
}

TEST(SettingText, AnErrorKeepsItsLiteralPartLiteral) {
  // A character's name from a stranger's file may hold braces: never a setting.
  SettingsUsageError error(" has no actions (pass {static} to bench that)", "{static}");
  EXPECT_STREQ(error.what(), "{static} has no actions (pass static to bench that)");
  EXPECT_EQ(error.spelled(as_option), "{static} has no actions (pass --static to bench that)");
  SettingsInputError input("b{x}.json", "differs ", "(record it again with {update_baseline})");
  EXPECT_STREQ(input.what(), "b{x}.json: differs (record it again with update_baseline)");
  EXPECT_EQ(input.spelled(as_option), "b{x}.json: differs (record it again with --update-baseline)");
}

}  // namespace
}  // namespace crowdprof
