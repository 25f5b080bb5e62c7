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
  if (std::memcmp(out.magic, "AMB1", 4) != 0) throw std::runtime_error(elf_path + ": unknown board descriptor version");
  out.board[sizeof out.board - 1] = 0;
  out.mcu[sizeof out.mcu - 1] = 0;
  if (out.axis_count > am::kMaxAxes) throw std::runtime_error(elf_path + ": corrupt board descriptor");
  return out;
}

}  // namespace sim
