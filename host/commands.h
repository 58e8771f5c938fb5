// commands.h — the subcommands of the fenestra CLI (host/main.cpp parses, these run).
#pragma once

namespace fen {

int runDevices(bool json);

}  // namespace fen
