// SPDX-License-Identifier: BSD-3-Clause
// Every kind of bad input file gives an lmk::Error that names the file and the problem.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

std::string pcd_header(const std::string& data, int width, int points,
                       const std::string& fields = "x y z") {
  return "VERSION 0.7\nFIELDS " + fields + "\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " +
         std::to_string(width) + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
         std::to_string(points) + "\nDATA " + data + "\n";
}

// The error from reading `path`; fails the test if reading succeeds.
std::string read_error(const std::string& path) {
  try {
    read_cloud(path);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "reading " << path << " did not fail";
  return "";
}

void expect_error(const std::string& path, const std::string& problem) {
  const std::string message = read_error(path);
  EXPECT_EQ(message.rfind(path, 0), 0u) << "message does not start with the path: " << message;
  EXPECT_NE(message.find(problem), std::string::npos) << "'" << problem << "' not in: " << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "message is not one line: " << message;
}

std::string truncate(const std::string& path, std::size_t keep) {
  const std::string bytes = test::read_bytes(path);
  const std::string out =
      path.substr(0, path.rfind('.')) + "_truncated" + path.substr(path.rfind('.'));
  test::write_text(out, bytes.substr(0, keep));
  return out;
}

class BadInput : public ::testing::Test {
 protected:
  test::ScratchDir dir_;
};

TEST_F(BadInput, MissingFile) { expect_error(dir_.file("absent.pcd"), "no such file"); }

TEST_F(BadInput, Directory) { expect_error(dir_.path().string(), "is a directory"); }

TEST_F(BadInput, UnknownExtension) {
  test::write_text(dir_.file("cloud.obj"), "v 0 0 0\n");
  expect_error(dir_.file("cloud.obj"), "unknown extension '.obj'");
}

TEST_F(BadInput, EmptyFile) {
  test::write_text(dir_.file("empty.ply"), "");
  expect_error(dir_.file("empty.ply"), "file is empty");
}

TEST_F(BadInput, GarbageInEveryFormat) {
  std::string garbage(4096, '\0');
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = static_cast<char>((i * 7919) % 251);
  for (const std::string ext : {".pcd", ".ply", ".xyz"}) {
    const std::string path = dir_.file("garbage" + ext);
    test::write_text(path, garbage);
    expect_error(path, "not a");
  }
}

TEST_F(BadInput, TruncatedBinaryPcdBinaryCompressedPcdAndPly) {
  const PointCloud cloud = test::random_cloud(1000, 1);
  for (const auto& [name, encoding] :
       std::vector<std::pair<std::string, Encoding>>{{"b.pcd", Encoding::kBinary},
                                                     {"c.pcd", Encoding::kBinaryCompressed},
                                                     {"b.ply", Encoding::kBinary},
                                                     {"a.ply", Encoding::kAscii},
                                                     {"a.pcd", Encoding::kAscii}}) {
    write_cloud(dir_.file(name), cloud, {encoding});
    const std::size_t size = std::filesystem::file_size(dir_.file(name));
    expect_error(truncate(dir_.file(name), size / 2), "truncated");
  }
}

TEST_F(BadInput, HeaderDeclaresMorePointsThanTheData) {
  test::write_text(dir_.file("more.pcd"), pcd_header("ascii", 4, 4) + "1 2 3\n4 5 6\n");
  expect_error(dir_.file("more.pcd"), "header declares 4 points but the data holds 2");
}

TEST_F(BadInput, HeaderDeclaresFewerPointsThanTheData) {
  test::write_text(dir_.file("fewer.pcd"), pcd_header("ascii", 1, 1) + "1 2 3\n4 5 6\n");
  expect_error(dir_.file("fewer.pcd"), "header declares 1 points but the data holds 2");
}

TEST_F(BadInput, WidthTimesHeightDisagreesWithPoints) {
  test::write_text(dir_.file("wh.pcd"), pcd_header("ascii", 5, 2) + "1 2 3\n4 5 6\n");
  expect_error(dir_.file("wh.pcd"), "WIDTH x HEIGHT = 5 x 1 but POINTS 2");
}

// Header declarations are checked before PCL sees them: a negative SIZE or COUNT crashed its body
// readers, and it allocates POINTS x point size while parsing the header.
TEST_F(BadInput, NegativeOrOddSizesAndCountsNeverReachPcl) {
  const std::string body(24, '\0');
  const auto header = [](const std::string& size, const std::string& count) {
    return "VERSION 0.7\nFIELDS x y z\nSIZE " + size + "\nTYPE F F F\nCOUNT " + count +
           "\nWIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA binary\n";
  };
  test::write_text(dir_.file("size.pcd"), header("-4 4 4", "1 1 1") + body);
  expect_error(dir_.file("size.pcd"), "header SIZE '-4' is not a count");
  test::write_text(dir_.file("count.pcd"), header("4 4 4", "-1 1 1") + body);
  expect_error(dir_.file("count.pcd"), "header COUNT '-1' is not a count");
  test::write_text(dir_.file("zero.pcd"), header("4 4 4", "0 1 1") + body);
  expect_error(dir_.file("zero.pcd"), "header COUNT 0 is not positive");
  test::write_text(dir_.file("odd.pcd"), header("3 4 4", "1 1 1") + body);
  expect_error(dir_.file("odd.pcd"), "header SIZE 3 is not 1, 2, 4 or 8 bytes");
  test::write_text(dir_.file("short.pcd"), header("4 4", "1 1") + body);
  expect_error(dir_.file("short.pcd"), "header lists 3 fields but 2 sizes and 2 counts");
}

TEST_F(BadInput, DeclaredPointsAreCheckedAgainstTheLimitAndTheBytesBeforeAllocating) {
  test::write_text(dir_.file("negative.pcd"), pcd_header("ascii", 1, -3) + "1 2 3\n");
  expect_error(dir_.file("negative.pcd"), "header POINTS '-3' is not a count");
  // 187 bytes declaring two billion points: refused at the limit, not by the OOM killer.
  test::write_text(dir_.file("huge.pcd"), pcd_header("binary", 2000000000, 2000000000) + "xyz");
  expect_error(dir_.file("huge.pcd"), "over lmk's limit of 50000000 points");
  test::write_text(dir_.file("binary.pcd"), pcd_header("binary", 1000000, 1000000) + "0123");
  expect_error(dir_.file("binary.pcd"),
               "truncated: header declares 1000000 points but the data holds at most 0");
  test::write_text(dir_.file("lzf.pcd"),
                   pcd_header("binary_compressed", 40000000, 40000000) + std::string(64, 'z'));
  expect_error(dir_.file("lzf.pcd"),
               "truncated: header declares 40000000 points but the data holds at most 533");
}

TEST_F(BadInput, NoXyzFields) {
  test::write_text(dir_.file("abc.pcd"), pcd_header("ascii", 1, 1, "a b c") + "1 2 3\n");
  expect_error(dir_.file("abc.pcd"), "no x/y/z fields (it has: a b c)");
  test::write_text(dir_.file("abc.ply"),
                   "ply\nformat ascii 1.0\nelement vertex 1\nproperty float a\nproperty float b\n"
                   "property float c\nend_header\n1 2 3\n");
  expect_error(dir_.file("abc.ply"), "no x/y/z fields");
}

TEST_F(BadInput, ZeroFinitePoints) {
  test::write_text(dir_.file("nan.pcd"), pcd_header("ascii", 2, 2) + "nan nan nan\nnan 1 2\n");
  expect_error(dir_.file("nan.pcd"), "none with finite x, y and z");
  test::write_text(dir_.file("none.xyz"), "# only a comment\n");
  expect_error(dir_.file("none.xyz"), "none with finite x, y and z");
}

TEST_F(BadInput, NonNumericAsciiData) {
  test::write_text(dir_.file("word.pcd"), pcd_header("ascii", 2, 2) + "1 2 3\n4 five 6\n");
  expect_error(dir_.file("word.pcd"), "data row 2: 'five' is not a number");
  test::write_text(dir_.file("short.pcd"), pcd_header("ascii", 2, 2) + "1 2 3\n4 5\n");
  expect_error(dir_.file("short.pcd"), "data row 2 has 2 values");
  test::write_text(dir_.file("word.xyz"), "1 2 3\n4 x 6\n");
  expect_error(dir_.file("word.xyz"), "line 2 does not start with three numbers");
}

std::string ply_header(int vertices) {
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
}

// PCL's ASCII PLY reader read "foo bar baz" as a NaN point and ignored rows beyond the count.
TEST_F(BadInput, AsciiPlyRowsAreNumbersAndAsManyAsDeclared) {
  test::write_text(dir_.file("word.ply"), ply_header(2) + "1 2 3\nfoo bar baz\n");
  expect_error(dir_.file("word.ply"), "data row 2: 'foo' is not a number");
  test::write_text(dir_.file("extra.ply"), ply_header(1) + "1 2 3\n4 5 6\n7 8 9\n");
  expect_error(dir_.file("extra.ply"), "header declares 1 data rows but the data holds 3");
  test::write_text(dir_.file("short.ply"), ply_header(2) + "1 2 3\n4 5\n");
  expect_error(dir_.file("short.ply"), "data row 2 has 2 values");
  test::write_text(dir_.file("negative.ply"), ply_header(-3) + "1 2 3\n");
  expect_error(dir_.file("negative.ply"), "malformed PLY element line: 'element vertex -3'");
  test::write_text(dir_.file("huge.ply"), ply_header(2000000000) + "1 2 3\n");
  expect_error(dir_.file("huge.ply"), "over lmk's limit of 50000000 points");
  // A well-formed file still reads.
  test::write_text(dir_.file("good.ply"), ply_header(2) + "1 2 3\n4 5 6\n");
  EXPECT_EQ(read_cloud(dir_.file("good.ply")).size(), 2u);
}

// PCL's header reader left the sensor pose uninitialised at "VIEWPOINT nan ...": every run saw
// another sensor origin.
TEST_F(BadInput, ViewpointMustBeSevenFiniteNumbers) {
  const std::string body = "1 2 3\n";
  for (const std::string viewpoint : {"nan 0 0 1 0 0 0", "0 0 0 1 0 0", "0 0 inf 1 0 0 0"}) {
    std::string header = pcd_header("ascii", 1, 1);
    header.replace(header.find("VIEWPOINT 0 0 0 1 0 0 0"), 23, "VIEWPOINT " + viewpoint);
    test::write_text(dir_.file("viewpoint.pcd"), header + body);
    expect_error(dir_.file("viewpoint.pcd"), "is not seven finite numbers");
  }
}

// PCL recognises a header keyword by its first letters: a fuzzed "SIZEF 1 1 1" line was a second
// SIZE to PCL, which laid out 1-byte floats that were then read as 4 bytes, past the data. lmk
// accepts a header only when PCL cannot read it another way.
TEST_F(BadInput, PcdHeaderLinesAreKeywordsSpeltExactlyOnce) {
  const std::string body = "1 2 3\n";
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string header = pcd_header("ascii", 1, 1);
    header.replace(header.find(from), from.size(), to);
    test::write_text(dir_.file("header.pcd"), header + body);
    return dir_.file("header.pcd");
  };
  expect_error(with("COUNT 1 1 1", "SIZEF 1 1 1"), "unknown header line 'SIZEF 1 1 1'");
  expect_error(with("COUNT 1 1 1", "SIZE 4 4 4"), "header SIZE is given twice");
  expect_error(with("COUNT 1 1 1", " COUNT 1 1 1"), "does not begin with its keyword");
  expect_error(with("COUNT 1 1 1", "COUNT\v1 1 1"), "holds a control character");
  expect_error(with("TYPE F F F", "TYPE F F X"), "header TYPE 'X' is not F, U or I");
  expect_error(with("SIZE 4 4 4", "SIZE 4 4 1"), "header TYPE F with SIZE 1: a float is 4 or 8");
  // PCL read on past DATA while lines looked like header lines: a body line "POINTS 2000000000"
  // made it allocate for two billion points (found by fuzzing). It is given the header alone.
  test::write_text(dir_.file("body.pcd"), pcd_header("ascii", 1, 1) + "POINTS 2000000000\n");
  expect_error(dir_.file("body.pcd"), "'POINTS' is not a number");
  // Comments, carriage returns and the keywords of older files still read.
  test::write_text(dir_.file("crlf.pcd"), "# made by hand\r\n" + pcd_header("ascii", 1, 1) + body);
  EXPECT_EQ(read_cloud(dir_.file("crlf.pcd")).size(), 1u);
}

// PCL's PLY reader writes a colour when it meets blue, where it met red: green and blue alone made
// it fail an assertion and abort (found by fuzzing).
TEST_F(BadInput, PlyColourPropertiesAreRedGreenBlueInOrder) {
  const auto ply_with = [&](const std::string& properties, const std::string& row) {
    test::write_text(dir_.file("colour.ply"),
                     "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
                     "y\nproperty float z\n" +
                         properties + "end_header\n1 2 3 " + row + "\n");
    return dir_.file("colour.ply");
  };
  const std::string problem = "vertex colour properties must be red, green and blue";
  expect_error(ply_with("property uchar green\nproperty uchar blue\n", "1 2"), problem);
  expect_error(ply_with("property uchar blue\nproperty uchar green\nproperty uchar red\n", "1 2 3"),
               problem);
  expect_error(
      ply_with("property uchar red\nproperty float q\nproperty uchar green\nproperty uchar blue\n",
               "1 0 2 3"),
      problem);
  expect_error(ply_with("property float q\nproperty float q\n", "1 2"), "'q' is declared twice");
  const PointCloud cloud = read_cloud(
      ply_with("property uchar red\nproperty uchar green\nproperty uchar blue\n", "10 20 30"));
  ASSERT_EQ(cloud.colors.size(), 1u);
  EXPECT_EQ(cloud.colors[0].g, 20);
}

// A file's bytes quoted in a message are escaped: the message stays one printable line.
TEST_F(BadInput, BinaryBytesAreEscapedInMessages) {
  test::write_text(dir_.file("junk.xyz"), std::string("1 2 3\n\x01\xff\xfe\x1b[31m junk\n"));
  const std::string message = read_error(dir_.file("junk.xyz"));
  EXPECT_NE(message.find("'\\x01\\xff\\xfe\\x1b[31m junk'"), std::string::npos) << message;
  for (const char c : message) EXPECT_GE(static_cast<unsigned char>(c), 0x20) << message;
  // UTF-8 text is kept as it is.
  EXPECT_EQ(printable("tasse \xc3\xa0 caf\xc3\xa9"), "tasse \xc3\xa0 caf\xc3\xa9");
  EXPECT_EQ(printable(std::string(100, 'a'), 10), "aaaaaaaaaa...");
}

// A named pipe blocked the open forever; a device could stream without end. Both are refused
// before anything opens them (the test would hang otherwise).
TEST_F(BadInput, SpecialFilesAreRefusedBeforeOpening) {
  const std::string pipe = dir_.file("pipe.pcd");
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  expect_error(pipe, "is a named pipe, not a point-cloud file");
  expect_error("/dev/zero", "is a character device");
  try {
    read_input_file(pipe, kProgramInput);
    ADD_FAILURE() << "a pipe was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is a named pipe, not a program file"), std::string::npos);
  }
}

// A file over its kind's ceiling is refused by its size, before it is read: a sparse file costs
// no disk.
TEST_F(BadInput, FilesOverTheirCeilingAreRefusedWithTheLimitNamed) {
  const std::string big = dir_.file("big.pcd");
  test::write_text(big, "x");
  ASSERT_EQ(::truncate(big.c_str(), static_cast<off_t>(kMaxCloudFileBytes + 1)), 0);
  expect_error(big, "is 4294967297 bytes, over lmk's limit of 4 GiB for a point-cloud file");
  const std::string json = dir_.file("big.json");
  test::write_text(json, "{}");
  ASSERT_EQ(::truncate(json.c_str(), static_cast<off_t>(kMaxTextFileBytes + 1)), 0);
  try {
    read_input_file(json, kDatasetInput);
    ADD_FAILURE() << "an oversized dataset file was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("over lmk's limit of 256 MiB for a dataset file"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace lmk
