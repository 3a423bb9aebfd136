// cloudgraph info FILE.

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>

#include "core/Hash.h"
#include "formats/PrimitiveFile.h"
#include "support/TestUtil.h"
#include "util/LittleEndian.h"
#include "util/SystemMemory.h"

namespace cg {

TEST(InfoCommand, SummarisesAPrimitiveFileAndRefusesADamagedOne)
{
    test::TempDir dir;
    formats::writePrimitiveFile(dir / "p.cgp", 2.0, {1, 2}, {0, 0, 1, 0, 0, 2, 3, 4, 5});
    const auto ok = test::runCli({"info", (dir / "p.cgp").string()});
    EXPECT_EQ(ok.exitCode, 0) << ok.errors;
    EXPECT_NE(ok.output.find("frames:      2"), std::string::npos) << ok.output;
    EXPECT_NE(ok.output.find("N_f(last) = 2"), std::string::npos) << ok.output;
    std::string bytes = test::readFile(dir / "p.cgp");
    bytes[bytes.size() - 12] ^= 1;
    test::writeFile(dir / "bad.cgp", bytes);
    const auto bad = test::runCli({"info", (dir / "bad.cgp").string()});
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.errors.find("bad.cgp:"), std::string::npos) << bad.errors;
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

TEST(InfoCommand, RefusesAFileOverTheMachinesLimitBeforeAllocatingIt)
{
    // Every reader of .cgp files refuses at the one machine-relative limit of a node's value.
    EXPECT_EQ(formats::maxPrimitiveFileBytes(), util::nodeAllocationLimitBytes());

    // A sparse file a little over the limit whose header and index are consistent and
    // checksummed: one frame that fills the file, so only the limit stands between `info` and
    // allocating the whole frame.
    test::TempDir dir;
    const std::uint64_t limit = util::nodeAllocationLimitBytes();
    const std::uint64_t prefix =
        formats::kPrimitiveHeaderBytes + formats::kPrimitiveIndexEntryBytes;
    const std::uint64_t count = (limit - prefix) / 12 + 1024;  // frame block: 16 + 12 N bytes
    ASSERT_LE(count, std::uint64_t{UINT32_MAX});
    std::string head = std::string("CGPRIM\r\n", 8);
    util::appendU32(head, formats::kPrimitiveFileVersion);
    util::appendU32(head, 1);    // frames
    util::appendF64(head, 1.0);  // Delta s
    util::appendU32(head, formats::kPrimitiveUnitsMetres);
    util::appendU32(head, 0);
    for (int k = 0; k < 6; ++k) util::appendF32(head, 0.0f);
    std::string index;
    util::appendU64(index, prefix);
    util::appendU32(index, static_cast<std::uint32_t>(count));
    util::appendU32(index, 0);
    const std::string checked = head + index;
    util::appendU64(head, checksum64(checked.data(), checked.size()));
    const auto file = dir / "forged.cgp";
    test::writeFile(file, head + index);
    std::filesystem::resize_file(file, prefix + 16 + 12 * count);

    // Address space capped at the limit: an allocation of the frame fails (bad_alloc, exit 1)
    // instead of taking the machine's memory, while a refusal needs far less. AddressSanitizer
    // reserves terabytes of shadow address space at start, so its build runs without the cap.
    const auto errors = dir / "errors.txt";
    const std::string cap =
        kAddressSanitizer ? "" : "ulimit -v " + std::to_string(limit / 1024) + " && ";
    const std::string command = cap + "exec '" + std::string(CLOUDGRAPH_CLI) + "' info '" +
                                file.string() + "' 2>'" + errors.string() + "' >/dev/null";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status)) << status;
    EXPECT_EQ(WEXITSTATUS(status), 2);
    const std::string message = test::readFile(errors);
    EXPECT_NE(message.find("forged.cgp"), std::string::npos) << message;
    EXPECT_NE(message.find("over the limit of " + std::to_string(limit)), std::string::npos)
        << message;
}

}  // namespace cg
