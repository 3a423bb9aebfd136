#include "core/PluginStamp.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

#if defined(__ELF__)
#include <elf.h>
#endif

namespace cg {

namespace {

[[noreturn]] void bad(const std::string& why) { throw std::runtime_error(why); }

/// Section name tables are small; a larger one is not from a library we can load.
constexpr std::uint64_t kMaxNameTableBytes = 1u << 20;

#if defined(__ELF__)
#if defined(__x86_64__)
constexpr std::uint16_t kMachine = EM_X86_64;
#elif defined(__aarch64__)
constexpr std::uint16_t kMachine = EM_AARCH64;
#else
constexpr std::uint16_t kMachine = EM_NONE;
#endif

void readExactly(const ByteSource& read, std::uint64_t fileSize, std::uint64_t offset, void* out,
                 std::uint64_t size, const char* what)
{
    if (offset > fileSize || size > fileSize - offset)
        bad(std::string(what) + " lies outside the file");
    if (!read(offset, out, static_cast<std::size_t>(size))) bad(std::string("cannot read ") + what);
}
#endif

}  // namespace

std::optional<std::int32_t> readPluginStamp(const ByteSource& read, std::uint64_t fileSize)
{
#if !defined(__ELF__)
    (void)read;
    (void)fileSize;
    return std::nullopt;  // no ELF: the loader relies on the entry function alone
#else
    Elf64_Ehdr eh{};
    if (fileSize < sizeof eh) bad("not an ELF library (too short)");
    readExactly(read, fileSize, 0, &eh, sizeof eh, "the ELF header");
    if (std::memcmp(eh.e_ident, ELFMAG, SELFMAG) != 0) bad("not an ELF library");
    if (eh.e_ident[EI_CLASS] != ELFCLASS64 || eh.e_ident[EI_DATA] != ELFDATA2LSB)
        bad("not a 64-bit little-endian ELF library");
    if (eh.e_type != ET_DYN) bad("not a shared library");
    if (kMachine != EM_NONE && eh.e_machine != kMachine)
        bad("built for another architecture (ELF machine " + std::to_string(eh.e_machine) + ")");
    if (eh.e_shentsize != sizeof(Elf64_Shdr) || eh.e_shnum == 0 || eh.e_shstrndx >= eh.e_shnum)
        bad("malformed ELF section header table");

    std::vector<Elf64_Shdr> sections(eh.e_shnum);
    readExactly(read, fileSize, eh.e_shoff, sections.data(),
                std::uint64_t{eh.e_shnum} * sizeof(Elf64_Shdr), "the section headers");
    const Elf64_Shdr& namesHeader = sections[eh.e_shstrndx];
    if (namesHeader.sh_size > kMaxNameTableBytes) bad("malformed ELF section name table");
    std::vector<char> names(static_cast<std::size_t>(namesHeader.sh_size) + 1, '\0');
    readExactly(read, fileSize, namesHeader.sh_offset, names.data(), namesHeader.sh_size,
                "the section names");

    const std::size_t wantedLength = std::strlen(kPluginStampSection);
    for (const Elf64_Shdr& s : sections) {
        if (s.sh_name >= namesHeader.sh_size) continue;
        const char* name = names.data() + s.sh_name;  // names ends with a '\0' we added
        if (std::strlen(name) != wantedLength || std::strcmp(name, kPluginStampSection) != 0)
            continue;
        // At least a stamp: AddressSanitizer pads globals with a redzone, section included.
        if (s.sh_type != SHT_PROGBITS || s.sh_size < sizeof(PluginStamp))
            bad(std::string("malformed ") + kPluginStampSection + " section");
        PluginStamp stamp{};
        readExactly(read, fileSize, s.sh_offset, &stamp, sizeof stamp, "the plugin stamp");
        if (std::memcmp(stamp.magic, kPluginStampMagic, sizeof stamp.magic) != 0)
            bad("the plugin stamp is damaged");
        return stamp.abiVersion;
    }
    return std::nullopt;
#endif
}

std::optional<std::int32_t> readPluginStampFromFile(const std::filesystem::path& path)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) bad(std::string("cannot open: ") + std::strerror(errno));
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) bad("not a regular file");
    const ByteSource read = [fd](std::uint64_t offset, void* out, std::size_t size) {
        auto* p = static_cast<unsigned char*>(out);
        while (size > 0) {
            const ssize_t n = ::pread(fd, p, size, static_cast<off_t>(offset));
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) return false;
            p += n;
            size -= static_cast<std::size_t>(n);
            offset += static_cast<std::uint64_t>(n);
        }
        return true;
    };
    return readPluginStamp(read, static_cast<std::uint64_t>(st.st_size));
}

}  // namespace cg
