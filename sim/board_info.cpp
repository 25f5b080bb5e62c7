#include "board_info.h"

#include <fcntl.h>
#include <gelf.h>
#include <libelf.h>
#include <unistd.h>

#include <cstring>
#include <stdexcept>

namespace sim {

am::BoardDescriptor read_board_descriptor(const std::string& elf_path) {
  if (elf_version(EV_CURRENT) == EV_NONE) throw std::runtime_error("libelf initialisation failed");
  const int fd = open(elf_path.c_str(), O_RDONLY);
  if (fd < 0) throw std::runtime_error("cannot open " + elf_path);
  Elf* elf = elf_begin(fd, ELF_C_READ, nullptr);
  am::BoardDescriptor out{};
  bool found = false;
  size_t shstrndx = 0;
  if (elf && elf_getshdrstrndx(elf, &shstrndx) == 0) {
    for (Elf_Scn* scn = elf_nextscn(elf, nullptr); scn; scn = elf_nextscn(elf, scn)) {
      GElf_Shdr shdr;
      if (!gelf_getshdr(scn, &shdr)) continue;
      const char* name = elf_strptr(elf, shstrndx, shdr.sh_name);
      if (!name || std::strcmp(name, ".avrmotion_board") != 0) continue;
      Elf_Data* data = elf_getdata(scn, nullptr);
      if (data && data->d_size == sizeof out) {
        std::memcpy(&out, data->d_buf, sizeof out);
        found = true;
      }
      break;
    }
  }
  if (elf) elf_end(elf);
  close(fd);
  if (!found) throw std::runtime_error(elf_path + ": no .avrmotion_board section (not an avrmotion image?)");
  if (std::memcmp(out.magic, "AMB4", 4) != 0) throw std::runtime_error(elf_path + ": unknown board descriptor version");
  out.board[sizeof out.board - 1] = 0;
  out.mcu[sizeof out.mcu - 1] = 0;
  if (out.axis_count > am::kMaxAxes) throw std::runtime_error(elf_path + ": corrupt board descriptor");
  return out;
}

ElfSymbol find_symbol(const std::string& elf_path, const std::string& mangled_name) {
  ElfSymbol out;
  if (elf_version(EV_CURRENT) == EV_NONE) return out;
  const int fd = open(elf_path.c_str(), O_RDONLY);
  if (fd < 0) return out;
  Elf* elf = elf_begin(fd, ELF_C_READ, nullptr);
  for (Elf_Scn* scn = elf ? elf_nextscn(elf, nullptr) : nullptr; scn && !out.found; scn = elf_nextscn(elf, scn)) {
    GElf_Shdr shdr;
    if (!gelf_getshdr(scn, &shdr) || shdr.sh_type != SHT_SYMTAB) continue;
    Elf_Data* data = elf_getdata(scn, nullptr);
    const size_t count = shdr.sh_entsize ? shdr.sh_size / shdr.sh_entsize : 0;
    for (size_t i = 0; data && i < count && !out.found; ++i) {
      GElf_Sym sym;
      if (!gelf_getsym(data, int(i), &sym)) continue;
      const char* name = elf_strptr(elf, shdr.sh_link, sym.st_name);
      if (name && mangled_name == name) out = ElfSymbol{uint32_t(sym.st_value), uint32_t(sym.st_size), true};
    }
  }
  if (elf) elf_end(elf);
  close(fd);
  return out;
}

uint16_t read_data_symbol(const std::string& elf_path, const std::string& mangled_name) {
  const ElfSymbol s = find_symbol(elf_path, mangled_name);
  if (!s.found) throw std::runtime_error(elf_path + ": no symbol " + mangled_name);
  return uint16_t(s.value & 0xFFFF);  // the data-space offset off
}

}  // namespace sim
