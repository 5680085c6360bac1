#pragma once
// The effect table: every effect of the frame, in the order they run (renderer/EffectTable.cpp). The one list the
// Renderer plans frames from, and the one everything else takes its lists from: the parameters (RenderSettings),
// the passes the timers and stats report, the targets the debug views show, the programs the shader checks build,
// the page's grouped controls, obscura-bench's per-effect figures.
#include <string>
#include <vector>

#include "frame/EffectEntry.h"

namespace obscura {

// The table, in frame order.
const std::vector<EffectEntry>& effectTable();
// The row named `effect`; throws InputError for an unknown name.
const EffectEntry& effectEntry(const std::string& effect);
// Every pass of the table, in frame order, then the frame's own "view" pass (debug views, split screen's copy).
const std::vector<std::string>& framePassNames();
// Every target of the table, in frame order.
const std::vector<TargetInfo>& frameTargets();
// The views a frame can show: "final", "split", then every target's views in table order.
const std::vector<std::string>& frameViewNames();
// Every program variant the frame may build: the table's, then the debug views'.
std::vector<ProgramSpec> frameProgramSpecs();

}  // namespace obscura
