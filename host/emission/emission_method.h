// emission_method.h — the names of the emission strategies (DESIGN.md §3); each is described once
// in emission/strategy_registry.cpp, which maps them to and from their --method names.
#pragma once

namespace fen {

enum class EmissionMethod { Uniform, Portal, Adaptive };

}  // namespace fen
