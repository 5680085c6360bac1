#include "frame/FramePlan.h"

#include <algorithm>
#include <set>
#include <tuple>

#include "base/Error.h"
#include "frame/Stage.h"

namespace obscura {
namespace {

std::string describe(const PlannedPass& pass) {
  return "pass '" + pass.decl.name + "'" + (pass.effect.empty() ? std::string() : " of effect '" + pass.effect + "'");
}

auto slotKind(const SlotKey& k) {
  return std::make_tuple(static_cast<int>(k.size.kind), k.size.tile, k.size.height, k.size.shiftX, k.size.shiftY,
                         k.filter, k.ownDepth);
}

}  // namespace

bool SlotKey::operator<(const SlotKey& o) const {
  return std::tuple_cat(slotKind(*this), std::make_tuple(index)) <
         std::tuple_cat(slotKind(o), std::make_tuple(o.index));
}
bool SlotKey::operator==(const SlotKey& o) const { return !(*this < o) && !(o < *this); }

bool FramePlanner::showsTargetOf(const EffectInfo& effect) const {
  return std::any_of(effect.targets.begin(), effect.targets.end(),
                     [&](const TargetInfo& target) { return target.name == viewTarget_; });
}

void FramePlanner::add(PassDecl pass) {
  if (pass.name.empty()) throw PipelineError("effect '" + effect_ + "' adds a pass without a name");
  entries_.push_back({effect_, std::move(pass), {}, {}, {}});
}

void FramePlanner::markExternal(const std::string& target) {
  if (entries_.empty() || entries_.back().decl.name.empty())
    throw PipelineError("effect '" + effect_ + "' marks '" + target + "' external before adding its pass");
  entries_.back().externalWrites.push_back(target);
}

void FramePlanner::alias(const std::string& name, const std::string& target) {
  entries_.push_back({effect_, PassDecl{}, {}, name, target});
}

bool FramePlanner::declares(const std::string& target) const {
  for (const Entry& entry : entries_) {
    if (entry.aliasName == target) return true;
    for (const PassDecl::Write& write : entry.decl.writes)
      if (write.target == target) return true;
  }
  return false;
}

FramePlan FramePlan::resolve(FramePlanner&& planner, const std::string& result,
                             const std::function<PassDecl()>& presentPass, const std::vector<std::string>& retain) {
  FramePlan plan;
  std::map<std::string, int> latest;  // target or alias -> the version reads bind to
  std::vector<std::map<std::string, int>> visible;  // per pass: `latest` as it stood before the pass

  auto addPass = [&](FramePlanner::Entry&& entry) {
    PlannedPass pass;
    pass.effect = std::move(entry.effect);
    pass.decl = std::move(entry.decl);
    const int index = static_cast<int>(plan.passes_.size());
    visible.push_back(latest);
    for (const std::string& read : pass.decl.reads) {
      const auto it = latest.find(read);
      if (it == latest.end())
        throw PipelineError(describe(pass) + " reads '" + read + "', which no earlier pass writes");
      pass.reads[read] = it->second;
    }
    for (const std::string& read : pass.decl.optionalReads) {
      const auto it = latest.find(read);
      if (it != latest.end()) pass.reads[read] = it->second;
    }
    for (const PassDecl::Write& write : pass.decl.writes) {
      TargetVersion version;
      version.target = write.target;
      version.writer = index;
      version.size = write.size;
      version.depth = write.depth;
      version.output = write.target == kOutputTarget;
      version.history = write.history;
      version.external = std::find(entry.externalWrites.begin(), entry.externalWrites.end(), write.target) !=
                         entry.externalWrites.end();
      if (!version.output) {
        const auto info = planner.targets_.find(write.target);
        if (info == planner.targets_.end())
          throw PipelineError(describe(pass) + " writes '" + write.target +
                              "', which its effect does not declare among its targets");
        version.filter = info->second.filter;
      }
      if (write.depth == PassDecl::Write::Depth::Shared) {
        const auto from = pass.reads.find(write.depthFrom);
        if (from != pass.reads.end()) {
          if (plan.versions_[static_cast<size_t>(from->second)].depth != PassDecl::Write::Depth::Own)
            throw PipelineError(describe(pass) + " shares the depth of '" + write.depthFrom + "', which has none");
          version.depthVersion = from->second;
        }
      }
      if (pass.writes.count(write.target))
        throw PipelineError(describe(pass) + " writes '" + write.target + "' twice");
      pass.writes[write.target] = static_cast<int>(plan.versions_.size());
      plan.versions_.push_back(version);
    }
    for (const auto& [target, version] : pass.writes) latest[target] = version;
    plan.passes_.push_back(std::move(pass));
  };

  for (FramePlanner::Entry& entry : planner.entries_) {
    if (entry.decl.name.empty()) {
      const auto it = latest.find(entry.aliasTarget);
      if (it == latest.end())
        throw PipelineError("effect '" + entry.effect + "' makes '" + entry.aliasName + "' an alias of '" +
                            entry.aliasTarget + "', which no earlier pass writes");
      latest[entry.aliasName] = it->second;
      continue;
    }
    addPass(std::move(entry));
  }

  // The result and who writes it.
  const auto resultIt = latest.find(result);
  if (resultIt == latest.end())
    throw PipelineError("no pass writes the frame's result '" + result + "'");
  const int resultVersion = resultIt->second;

  for (const std::string& target : retain) {
    const auto it = latest.find(target);
    if (it == latest.end()) throw InputError("no pass writes '" + target + "' with these settings");
    plan.retained_[target] = it->second;
  }

  // Liveness, backwards: reads only point at earlier passes.
  std::set<int> needed = {resultVersion};
  for (const auto& [target, version] : plan.retained_) needed.insert(version);
  for (int i = static_cast<int>(plan.passes_.size()) - 1; i >= 0; --i) {
    PlannedPass& pass = plan.passes_[static_cast<size_t>(i)];
    pass.live = pass.decl.keep ||
                std::any_of(pass.writes.begin(), pass.writes.end(), [&](auto& w) { return needed.count(w.second); });
    if (!pass.live) continue;
    for (const std::string& read : pass.decl.reads) needed.insert(pass.reads[read]);
  }
  auto writerLive = [&](int version) {
    return plan.passes_[static_cast<size_t>(plan.versions_[static_cast<size_t>(version)].writer)].live;
  };
  // Whether a stage head may draw `contents` (what it writes) into the output: where it says it may, and, for one that
  // keeps the depth it shares, where the pass that depth comes from does not run.
  auto mayDrawIntoOutput = [&](const StageHead& head, const TargetVersion& contents) {
    const bool sharesLiveDepth = contents.depth == PassDecl::Write::Depth::Shared && contents.depthVersion >= 0 &&
                                 writerLive(contents.depthVersion);
    return head.mayWriteOutput && !(head.keepsSharedDepth && sharesLiveDepth);
  };
  for (PlannedPass& pass : plan.passes_)
    for (const std::string& read : pass.decl.optionalReads) {
      const auto it = pass.reads.find(read);
      if (it != pass.reads.end() && !writerLive(it->second)) pass.reads.erase(it);
    }

  // Alternatives, now that it is known which passes run.
  auto readersOf = [&](int version) {
    std::vector<int> readers;
    for (int j = 0; j < static_cast<int>(plan.passes_.size()); ++j) {
      const PlannedPass& other = plan.passes_[static_cast<size_t>(j)];
      if (!other.live) continue;
      for (const auto& [target, read] : other.reads)
        if (read == version) {
          readers.push_back(j);
          break;
        }
    }
    return readers;
  };
  auto retainedVersion = [&](int version) {
    for (const auto& [target, v] : plan.retained_)
      if (v == version) return true;
    return false;
  };
  for (int i = 0; i < static_cast<int>(plan.passes_.size()); ++i) {
    PlannedPass& pass = plan.passes_[static_cast<size_t>(i)];
    if (!pass.live) continue;
    for (const PassDecl::Alternative& alternative : pass.decl.alternatives) {
      const std::map<std::string, int>& seen = visible[static_cast<size_t>(i)];
      auto written = [&](const std::string& target) {
        const auto it = seen.find(target);
        return it != seen.end() && writerLive(it->second);
      };
      if (!std::all_of(alternative.whenWritten.begin(), alternative.whenWritten.end(), written) ||
          !std::all_of(alternative.reads.begin(), alternative.reads.end(), written))
        continue;
      int absorbed = -1;
      if (!alternative.absorbing.empty()) {
        // The one running reader of everything this pass writes, reading nothing else.
        std::set<int> readers;
        bool kept = false;
        for (const auto& [target, version] : pass.writes) {
          for (int j : readersOf(version)) readers.insert(j);
          kept = kept || version == resultVersion || retainedVersion(version);
        }
        if (kept || readers.size() != 1) continue;
        const PlannedPass& reader = plan.passes_[static_cast<size_t>(*readers.begin())];
        if (reader.decl.name != alternative.absorbing) continue;
        bool readsOnlyThis = true;
        for (const auto& [target, version] : reader.reads)
          readsOnlyThis = readsOnlyThis && plan.versions_[static_cast<size_t>(version)].writer == i;
        bool used = true;  // its results are read, or (where allowed) are the frame's result
        for (const auto& [target, version] : reader.writes)
          used = used && (!readersOf(version).empty() || retainedVersion(version) ||
                          (alternative.mayWriteOutput && version == resultVersion));
        if (!readsOnlyThis || !used) continue;
        absorbed = *readers.begin();
      }
      // Take it: the alternative's reads, its code, its writes (this pass's targets, or the absorbed pass's) and what
      // it offers stages.
      std::map<std::string, int> writes =
          absorbed >= 0 ? plan.passes_[static_cast<size_t>(absorbed)].writes : pass.writes;
      if (writes.size() != alternative.writes.size())
        throw PipelineError(describe(pass) + ": an alternative writes other targets than it stands in for");
      pass.reads.clear();
      for (const std::string& read : alternative.reads) pass.reads[read] = seen.at(read);
      for (const PassDecl::Write& write : alternative.writes) {
        const auto it = writes.find(write.target);
        if (it == writes.end())
          throw PipelineError(describe(pass) + ": an alternative writes '" + write.target + "', which it stands in "
                              "for no pass writing");
        TargetVersion& version = plan.versions_[static_cast<size_t>(it->second)];
        version.writer = i;
        version.size = write.size;
        version.depth = write.depth;
        version.depthVersion = -1;
        if (write.depth == PassDecl::Write::Depth::Shared && pass.reads.count(write.depthFrom))
          version.depthVersion = pass.reads.at(write.depthFrom);
      }
      if (absorbed >= 0) {
        plan.passes_[static_cast<size_t>(absorbed)].live = false;
        pass.absorbed.push_back(plan.passes_[static_cast<size_t>(absorbed)].decl.name);
      }
      pass.writes = writes;
      pass.decl.reads = alternative.reads;
      pass.decl.optionalReads.clear();
      pass.decl.writes = alternative.writes;
      pass.decl.run = alternative.run;
      pass.decl.stageHead = alternative.stageHead;
      break;
    }
  }

  // Per-pixel stages fuse into the stage head before them (rule 4b).
  for (int i = 0; i < static_cast<int>(plan.passes_.size()); ++i) {
    PlannedPass& head = plan.passes_[static_cast<size_t>(i)];
    if (!head.live || !head.decl.stageHead) continue;
    const StageHead& offer = *head.decl.stageHead;
    head.stageOutput = offer.color;
    if (!planner.fuseStages_) continue;
    ColorSpace space = offer.space;
    int vectors = offer.uniformVectors;
    int units = offer.textureUnits;
    for (;;) {
      const auto own = head.writes.find(head.stageOutput);
      if (own == head.writes.end()) break;
      const int color = own->second;
      if (color == resultVersion || retainedVersion(color)) break;
      const std::vector<int> readers = readersOf(color);
      if (readers.size() != 1) break;
      PlannedPass& next = plan.passes_[static_cast<size_t>(readers.front())];
      if (!next.decl.stage || next.writes.size() != 1) break;
      const StageDecl& stage = *next.decl.stage;
      const auto input = next.reads.find(stage.input);
      if (input == next.reads.end() || input->second != color || stage.inputSpace != space) break;
      if (stage.uniformVectors > vectors) break;
      if ((stage.position || stage.normal) && !offer.pixelGeometry) break;
      if (!stage.textures.empty() && !offer.bindsTextures) break;
      const int stageUnits = static_cast<int>(stage.textures.size() + stage.ownTextures.size());
      if (stageUnits > 0 && stageUnits > units) break;
      // What else it reads, the head must see as it is: written before the head runs.
      bool readable = true;
      for (const auto& [target, version] : next.reads) {
        if (target == stage.input) continue;
        const auto mine = head.reads.find(target);
        readable = readable && plan.versions_[static_cast<size_t>(version)].writer < i &&
                   (mine == head.reads.end() || mine->second == version);
      }
      if (!readable) break;
      const int output = next.writes.begin()->second;
      TargetVersion& out = plan.versions_[static_cast<size_t>(output)];
      const TargetVersion& in = plan.versions_[static_cast<size_t>(color)];
      if (!(out.size == in.size) || out.history || out.external) break;
      const bool drawnIntoOutput = output == resultVersion && readersOf(output).empty() && !retainedVersion(output);
      if (drawnIntoOutput && !mayDrawIntoOutput(offer, in)) break;
      // Fuse: the head writes the stage's output, with its own depth set-up, and reads what the stage reads.
      vectors -= stage.uniformVectors;
      units -= stageUnits;
      space = stage.outputSpace;
      head.stages.push_back(stage);
      head.absorbed.push_back(next.decl.name);
      next.live = false;
      out.writer = i;
      out.depth = in.depth;
      out.depthVersion = in.depthVersion;
      head.writes.erase(own);
      head.writes[out.target] = output;
      head.stageOutput = out.target;
      for (const auto& [target, version] : next.reads)
        if (target != stage.input) head.reads[target] = version;
    }
  }

  for (PlannedPass& pass : plan.passes_) pass.stagesName = fusedProgramName("", pass.stages);

  for (PlannedPass& pass : plan.passes_) {
    for (const auto& [target, version] : pass.writes) {
      TargetVersion& v = plan.versions_[static_cast<size_t>(version)];
      if (v.depth == PassDecl::Write::Depth::Shared && (v.depthVersion < 0 || !writerLive(v.depthVersion))) {
        v.depth = PassDecl::Write::Depth::Own;  // nothing to share this frame: the pass clears its own
        v.depthVersion = -1;
      }
    }
  }

  // The result goes straight into the output unless a running pass reads it too.
  TargetVersion& resultContents = plan.versions_[static_cast<size_t>(resultVersion)];
  bool resultRead = false;
  for (const PlannedPass& pass : plan.passes_)
    for (const auto& [target, version] : pass.reads) resultRead = resultRead || (pass.live && version == resultVersion);
  for (const auto& [target, version] : plan.retained_) resultRead = resultRead || version == resultVersion;
  if (!resultContents.output) {
    // A stage head that cannot draw into the output (StageHead::mayWriteOutput) leaves its result to a copy.
    const auto& writerHead = resultContents.writer >= 0
                                 ? plan.passes_[static_cast<size_t>(resultContents.writer)].decl.stageHead
                                 : std::optional<StageHead>();
    const bool writerMay = !writerHead || mayDrawIntoOutput(*writerHead, resultContents);
    if (!resultRead && !resultContents.external && !resultContents.history && writerMay) {
      resultContents.output = true;
      // The output has no other pass's depth: one that depth-tests there uses the output's own
      // (FrameContext::outputDepth), which it clears.
      if (resultContents.depth == PassDecl::Write::Depth::Shared) {
        resultContents.depth = PassDecl::Write::Depth::Own;
        resultContents.depthVersion = -1;
      }
    } else {
      FramePlanner::Entry present{"", presentPass(), {}, {}, {}};
      addPass(std::move(present));
      PlannedPass& copy = plan.passes_.back();
      copy.live = true;
      if (copy.reads.count(result) == 0 || copy.reads.at(result) != resultVersion || copy.writes.size() != 1 ||
          !plan.versions_[static_cast<size_t>(copy.writes.begin()->second)].output)
        throw PipelineError("the present pass must read '" + result + "' and write the output");
    }
  }

  for (int i = 0; i < static_cast<int>(plan.passes_.size()); ++i) {
    const PlannedPass& pass = plan.passes_[static_cast<size_t>(i)];
    if (!pass.live) continue;
    for (const auto& [target, version] : pass.reads) plan.versions_[static_cast<size_t>(version)].lastReader = i;
  }
  // Retained contents are read after the frame: after every pass.
  for (const auto& [target, version] : plan.retained_)
    plan.versions_[static_cast<size_t>(version)].lastReader = static_cast<int>(plan.passes_.size());

  // Slots: the lowest free index of the right kind, free again after the last pass reading it.
  std::set<SlotKey> inUse;
  for (int i = 0; i < static_cast<int>(plan.passes_.size()); ++i) {
    const PlannedPass& pass = plan.passes_[static_cast<size_t>(i)];
    if (!pass.live) continue;
    for (const auto& [target, version] : pass.writes) {
      TargetVersion& v = plan.versions_[static_cast<size_t>(version)];
      if (v.output || v.external || v.history) continue;
      SlotKey key{v.size, v.filter, v.depth == PassDecl::Write::Depth::Own, 0};
      while (inUse.count(key)) ++key.index;
      inUse.insert(key);
      v.slot = key;
    }
    for (TargetVersion& v : plan.versions_) {
      if (!v.slot || !plan.passes_[static_cast<size_t>(v.writer)].live) continue;
      const int lastUse = std::max(v.lastReader, v.writer);
      if (lastUse == i) inUse.erase(*v.slot);
    }
  }
  return plan;
}

int FramePlan::retainedVersion(const std::string& target) const {
  const auto it = retained_.find(target);
  return it == retained_.end() ? -1 : it->second;
}

std::vector<SlotKey> FramePlan::slots() const {
  std::set<SlotKey> keys;
  for (const TargetVersion& v : versions_)
    if (v.slot && passes_[static_cast<size_t>(v.writer)].live) keys.insert(*v.slot);
  return {keys.begin(), keys.end()};
}

}  // namespace obscura
