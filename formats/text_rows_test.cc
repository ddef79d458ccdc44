#include "formats/text_rows.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <vector>

namespace atlas::formats {
namespace {

std::vector<std::vector<std::string>> Rows(std::string_view text, size_t fields,
                                           std::string* error) {
  std::vector<std::vector<std::string>> rows;
  *error = ForEachRow(text, "f.tsv", fields, "a b", [&](auto f, int64_t line) {
    rows.push_back({std::to_string(line)});
    for (std::string_view s : f) rows.back().emplace_back(s);
    return std::string();
  });
  return rows;
}

TEST(TextRows, SplitsAtSpacesAndTabsAndSkipsCommentsAndBlankLines) {
  std::string error;
  const auto rows = Rows("# header\n\n1\t2\r\n   # indented comment\n  3  \t 4 \n5 6", 2, &error);
  ASSERT_EQ(error, "");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"3", "1", "2"}));
  EXPECT_EQ(rows[1], (std::vector<std::string>{"5", "3", "4"}));
  EXPECT_EQ(rows[2], (std::vector<std::string>{"6", "5", "6"}));
}

TEST(TextRows, ErrorsNameFileAndLine) {
  std::string error;
  Rows("1 2\n1 2 3\n", 2, &error);
  EXPECT_EQ(error, "f.tsv:2: expected 2 fields (a b), found 3");
  error = ForEachRow("# h\n1 2\n", "f.tsv", 2, "a b",
                     [](auto, int64_t) { return std::string("no good"); });
  EXPECT_EQ(error, "f.tsv:2: no good");
}

TEST(TextRows, FieldChecks) {
  double v = 0;
  EXPECT_EQ(NumberField("+1.5", 1, &v), "");
  EXPECT_EQ(v, 1.5);
  EXPECT_EQ(NumberField("nan", 3, &v), "field 3 is 'nan', not a number");
  EXPECT_EQ(NumberField("1,5", 2, &v), "field 2 is '1,5', not a number");
  FrameId f = 0;
  EXPECT_EQ(FrameField("-1", 2, true, &f), "");
  EXPECT_EQ(f, kNoFrame);
  EXPECT_NE(FrameField("-1", 2, false, &f), "");
  EXPECT_NE(FrameField("1.0", 2, false, &f), "");
  Time t{};
  EXPECT_EQ(StampField("1.25", 1, &t), "");
  EXPECT_EQ(t, FromSeconds(1.25));
  EXPECT_EQ(StampField("1e300", 1, &t).rfind("field 1 (a timestamp) is 1e+300, out of range", 0),
            0u);
  Pose2 p;
  const std::vector<std::string_view> fields = {"x", "1", "2", "7.0"};
  EXPECT_EQ(PoseFields(fields, 1, &p), "");
  EXPECT_NEAR(p.theta, 7.0 - 2 * std::numbers::pi, 1e-12);  // wrapped
  const std::vector<std::string_view> far = {"1e8", "0", "0"};
  EXPECT_EQ(PoseFields(far, 0, &p).rfind("field 1 is 1e+08, out of range for a position", 0), 0u);
}

TEST(TextRows, ReadsPlainAndGzipFilesAndWrites) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "text_rows_test";
  std::filesystem::create_directories(dir);
  const std::string plain = (dir / "a.tsv").string();
  ASSERT_EQ(WriteTextFile(plain, "1 2\n"), "");
  EXPECT_EQ(ReadTextFile(plain).text, "1 2\n");
  const std::string gz = (dir / "a.tsv.gz").string();
  gzFile f = gzopen(gz.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  gzputs(f, "3 4\n");
  gzclose(f);
  const TextFile read = ReadTextFile(gz);
  EXPECT_EQ(read.error, "");
  EXPECT_EQ(read.text, "3 4\n");
  const TextFile missing = ReadTextFile((dir / "none.tsv").string());
  EXPECT_TRUE(missing.missing);
  EXPECT_EQ(missing.error.rfind((dir / "none.tsv").string() + ": cannot open (", 0), 0u);
  EXPECT_EQ(WriteTextFile((dir / "no" / "such.tsv").string(), "x").rfind("cannot write ", 0), 0u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace atlas::formats
