#include "cli/commands.h"

namespace windplan::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> list = {
  };
  return list;
}

}  // namespace windplan::cli
