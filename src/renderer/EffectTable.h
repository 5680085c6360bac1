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
// Every program variant the frame may build: the table's, the fused programs of per-pixel stages (fusedProgramSpecs),
// then the debug views'.
std::vector<ProgramSpec> frameProgramSpecs();
// The fused programs the shader checks build (frame/Stage.h): each stage variant alone, and in pairs of stages that
// follow each other, each in a stand-alone stage pass and in every program stages fuse into (the lighting's forms).
// A frame builds the chains its plans fuse, on first use.
std::vector<ProgramSpec> fusedProgramSpecs();

}  // namespace obscura
