// core::EnumNames: one table of {name, value} pairs per enum parses the
// names users type (exact spelling only), prints a value's name, and lists
// the names for messages, CLI11 checks and TableReader::getChoice.

#include "core/enum_names.hpp"
#include "core/toml_reader.hpp"

#include <gtest/gtest.h>

namespace core = lamina::core;

namespace {

enum class Fruit { Apple, Pear, Quince };

constexpr auto kFruitNames = core::enumNames<Fruit>(
    {{"apple", Fruit::Apple}, {"pear", Fruit::Pear}, {"quince", Fruit::Quince}});

// A value with two names (an alias): the first is the one printed.
enum class Width { Narrow, Wide };
constexpr auto kWidthNames =
    core::enumNames<Width>({{"narrow", Width::Narrow}, {"wide", Width::Wide}, {"w", Width::Wide}});

// The table is usable at compile time.
static_assert(kFruitNames.size() == 3);
static_assert(kFruitNames.parse("pear") == Fruit::Pear);
static_assert(kFruitNames.name(Fruit::Quince) == "quince");

} // namespace

TEST(EnumNames, ParsesEveryNameAndPrintsItBack) {
  for (const auto& [name, value] : kFruitNames) {
    ASSERT_TRUE(kFruitNames.parse(name).has_value()) << name;
    EXPECT_EQ(*kFruitNames.parse(name), value);
    EXPECT_EQ(kFruitNames.name(value), name);
  }
}

TEST(EnumNames, RefusesAnyOtherSpelling) {
  for (const char* wrong : {"Apple", "apple ", " pear", "pea", "", "quinces", "APPLE"})
    EXPECT_FALSE(kFruitNames.parse(wrong).has_value()) << "'" << wrong << "'";
}

TEST(EnumNames, AnAliasParsesAndTheFirstNameIsPrinted) {
  EXPECT_EQ(kWidthNames.parse("w"), Width::Wide);
  EXPECT_EQ(kWidthNames.parse("wide"), Width::Wide);
  EXPECT_EQ(kWidthNames.name(Width::Wide), "wide");
}

TEST(EnumNames, ListsTheNamesForMessagesAndTheCommandLine) {
  EXPECT_EQ(kFruitNames.list(), "'apple', 'pear' or 'quince'");
  EXPECT_EQ(kFruitNames.list('"'), "\"apple\", \"pear\" or \"quince\"");
  EXPECT_EQ(kFruitNames.names(), (std::vector<std::string>{"apple", "pear", "quince"}));
  EXPECT_EQ(core::choiceList({"one"}), "'one'");
  EXPECT_EQ(core::choiceList({"one", "two"}), "'one' or 'two'");
  EXPECT_EQ(core::choiceList({}), "");
}

TEST(EnumNames, AnUnknownNameIsAnErrorNamingWhatAndWhereAndTheChoices) {
  EXPECT_EQ(kFruitNames.parseOrThrow("pear", "fruit", {}), Fruit::Pear);
  try {
    kFruitNames.parseOrThrow("plum", "fruit", {"basket.toml", 3, "basket.fruit"});
    FAIL() << "plum accepted";
  } catch (const lamina::Error& e) {
    EXPECT_EQ(e.context().file, "basket.toml");
    EXPECT_EQ(e.context().line, 3);
    EXPECT_EQ(e.message(), "unknown fruit 'plum' (expected 'apple', 'pear' or 'quince')");
  }
}

TEST(EnumNames, TableReaderReadsAKeyThroughTheTable) {
  const toml::table doc = core::parseTomlString("a = \"quince\"\nb = \"plum\"\n", "basket.toml");
  const core::TableReader root(doc, "basket.toml");
  EXPECT_EQ(root.getChoice("a", kFruitNames), Fruit::Quince);
  EXPECT_EQ(root.getChoice("absent", kFruitNames, Fruit::Pear), Fruit::Pear);
  try {
    root.getChoice("b", kFruitNames);
    FAIL() << "plum accepted";
  } catch (const lamina::Error& e) {
    EXPECT_EQ(e.context().key, "b");
    EXPECT_NE(std::string(e.what()).find(
                  "unknown value \"plum\" (expected \"apple\", \"pear\" or \"quince\")"),
              std::string::npos)
        << e.what();
  }
}
