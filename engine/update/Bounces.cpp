// After the link update: further bounces (paper sec. 5.3.2) carry the change
// of radiosity the partial push-pull (Fig. 7) found through the links leaving
// each changed element, until nothing moves by more than the threshold or a
// deadline leaves no time for another bounce (the rest waits, unsent); then
// refinement follows the light (OracleSteps.h): the links of elements whose
// oracle stepped are judged again.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include <tbb/parallel_for.h>

#include "refine/Refiner.h"
#include "solve/ClusterTransfer.h"
#include "solve/Solver.h"
#include "update/LineSpaceUpdate.h"
#include "update/OracleSteps.h"
#include "update/Timing.h"

namespace rad {

namespace {

// Keeps in `v` its items of highest priority whose costs add up to `share`
// of the total (at least one), in that order, and hands the others to `rest`.
template <class T, class Cost, class Priority, class Rest>
void keepShare(std::vector<T>& v, double share, const Cost& cost, const Priority& priority, const Rest& rest) {
    std::vector<std::pair<double, std::size_t>> order;  // (priority, index in v)
    order.reserve(v.size());
    double total = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        order.emplace_back(priority(v[i]), i);
        total += cost(v[i]);
    }
    std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<T> kept;
    double used = 0.0;
    for (const auto& [p, i] : order) {
        used += cost(v[i]);
        if (kept.empty() || used <= share * total)
            kept.push_back(v[i]);
        else
            rest(v[i]);
    }
    v.swap(kept);
}

}  // namespace

void LineSpaceUpdate::bounce(std::vector<ElementId> visited, const UpdateSettings& settings, FrameStats& stats) {
    // Timed whichever way it returns (the budget's fit leaves it out).
    const struct BounceTimer {
        FrameStats& stats;
        std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
        ~BounceTimer() { stats.bounceSeconds += secondsSince(start); }
    } timer{stats};
    // A move's frames send only the larger changes; what lies between the
    // two thresholds waits, unsent, for the next frame or idle time.
    const double sendAll = settings.bounceThreshold * reference();
    const double threshold = moving_ ? std::max(settings.moveBounceThreshold * reference(), sendAll) : sendAll;
    // Past the deadline nothing is sent, and the senders wait without being
    // read (a catch-up push of the building floor visits 100,000 to 170,000
    // elements: counting their links one by one, a cache miss each, took 2
    // to 6 ms of frames already over).
    if (deadline_ && !idle_ && shareThatFits(stats.changedLeaves, 0.0) == 0.0) {
        holdUnsent(visited);
        return;
    }
    // What a deadline kept earlier frames from sending goes out with this
    // frame's changes, when a share of it fits, and choosing that share
    // (reading every candidate, ordering them by power) fits too. Otherwise
    // this frame's senders join it without its elements being read again
    // (on the building floor 170,000 waited: reading them took 6 ms a frame,
    // choosing among them 16 ms).
    bool sendNone = false;
    if (!unsent_.empty()) {
        std::size_t links = unsentLinks_;
        for (ElementId e : visited) links += h_[e].outLinks.size();
        const double choosing = chooseSecondsPerSender_ * double(unsent_.size() + visited.size());
        sendNone = !idle_ && (shareThatFits(stats.changedLeaves, choosing) < 1.0 ||
                              shareThatFits(stats.changedLeaves, bounceSecondsPerLink_ * double(links) + choosing) <
                                  kLeastShare);
        if (sendNone) {
            for (ElementId e : visited)
                if (const std::size_t n = h_[e].outLinks.size()) joinUnsent(e, n);
        } else {
            // The unsent join the senders, each once (marks kept zero
            // between calls: a new array of the building floor's 623,000
            // elements faulted 0.6 MB in each time, about 1.7 ms).
            if (sending_.size() < h_.size()) sending_.resize(h_.size(), 0);
            const std::size_t fromThisFrame = visited.size();
            for (ElementId e : visited) sending_[e] = 1;
            for (ElementId e : unsent_.members())
                if (!std::exchange(sending_[e], 1)) visited.push_back(e);
            for (std::size_t i = 0; i < fromThisFrame; ++i) sending_[visited[i]] = 0;
            for (ElementId e : unsent_.members()) sending_[e] = 0;
            unsent_.clear();
            unsentLinks_ = 0;
        }
    }
    BounceSeries series;
    for (int b = 0; b < settings.maxBounces && !sendNone; ++b) {
        // On a deadline: a bounce, expected to cost per link leaving its
        // senders what the last one did (its push and meshing included), is
        // made only in the share that leaves the frame its time, by the
        // senders with the most power to send; the others wait, unsent. (By
        // the last bounce's whole cost instead, a bounce from half the
        // building floor after one from a chair's neighbours took 50 ms of a
        // 33 ms frame.) Each sender is read once here: a bounce may begin
        // from 100,000 elements, and each reading of one is a cache miss.
        const auto choosingStart = std::chrono::steady_clock::now();
        const std::size_t candidates = visited.size();
        std::vector<std::pair<ElementId, std::size_t>> senders;  // and the links leaving it
        std::size_t links = 0;
        for (ElementId e : visited)
            if (const std::size_t n = h_[e].outLinks.size()) {
                senders.emplace_back(e, n);
                links += n;
            }
        double share = idle_ && b == 0 ? 1.0
                                       : shareThatFits(stats.changedLeaves,
                                                       bounceSecondsPerLink_ * double(links));
        if (share < 1.0) {
            // Choosing the share reads every sender and orders them: its
            // time comes first (at 30 fps in `two-offices`, 6 to 9 ms for
            // 100,000 senders, and such frames ran 5 ms over).
            const double rate = cutBounceSecondsPerLink_ > 0.0
                                    ? cutBounceSecondsPerLink_
                                    : kCutBounceGuess * bounceSecondsPerLink_;
            share = shareThatFits(stats.changedLeaves, rate * double(links), chooseSecondsPerSender_ * double(candidates));
        }
        if (share < kLeastShare) {
            for (const auto& [e, n] : senders) joinUnsent(e, n);
            break;
        }
        // On a deadline a large bounce is sent in runs of senders of about
        // kBounceRunLinks links, those with the most power first, and the
        // clock is looked at between runs at the rate this bounce's runs
        // took: the rate learnt from earlier bounces misjudges one whose
        // transfers reach receivers all over the scene (a random room of
        // `bench/untuned/random_room.py` at 60 fps: 341,000 links expected at
        // 9 ns each took 27 ms). The senders the clock leaves wait, unsent.
        const bool inRuns = deadline_ && !idle_ && links > kBounceRunLinks;
        // Cut to its share, or only put in that order for the runs.
        if (share < 1.0 || inRuns) {
            using Sender = std::pair<ElementId, std::size_t>;
            keepShare(
                senders, share, [](const Sender& s) { return double(s.second); },
                [&](const Sender& s) { return unsentPowerOf(s.first); },
                [&](const Sender& s) { joinUnsent(s.first, s.second); });
            links = 0;
            for (const auto& [e, n] : senders) links += n;
        }
        if (candidates >= kPushSample)
            chooseSecondsPerSender_ =
                std::max(secondsSince(choosingStart) / double(candidates), 0.75 * chooseSecondsPerSender_);
        const auto began = std::chrono::steady_clock::now();
        const std::size_t leavesBefore = stats.changedLeaves;
        // A bounce that leaves senders unsent, or may, is no term of the series.
        if (share < 1.0 || inRuns) series.last = series.ratio = glm::dvec3(-1.0);
        bool sent = false;
        std::size_t sentLinks = 0;
        std::vector<ElementId> held;
        for (std::size_t next = 0; next < senders.size();) {
            std::size_t runLinks = 0, end = next;
            while (end < senders.size() && (!inRuns || end == next || runLinks < kBounceRunLinks)) runLinks += senders[end++].second;
            if (inRuns && sentLinks > 0 &&
                shareThatFits(stats.changedLeaves, secondsSince(began) / double(sentLinks) * double(runLinks)) < 1.0) {
                for (; next < senders.size(); ++next) joinUnsent(senders[next].first, senders[next].second);
                break;
            }
            visited.clear();
            for (std::size_t i = next; i < end; ++i) visited.push_back(senders[i].first);
            held.clear();
            sent = sendTransfers(visited, {threshold, sendAll, settings.moveBounceThreshold},
                                 share < 1.0 || inRuns || !settings.extrapolateBounces ? nullptr : &series, held,
                                 stats.transfers) ||
                   sent;
            for (ElementId e : held) joinUnsent(e, h_[e].outLinks.size());
            sentLinks += runLinks;
            next = end;
        }
        links = sentLinks;
        if (!sent) break;
        ++stats.bounces;
        std::erase_if(waiting_, [&](ElementId e) {
            if (!h_[e].dirty) return false;
            waitingChange_[e] = -1.0;  // pushed now
            return true;
        });
        visited = pushPull(stats, true);
        touch(visited);
        // What was sent ahead is a sender until its radiosity has come to
        // what it sent (each bounce checks it against the threshold), even
        // where no push visits it again.
        if (!series.sentAhead.empty()) {
            visited.insert(visited.end(), series.sentAhead.begin(), series.sentAhead.end());
            std::sort(visited.begin(), visited.end());
            visited.erase(std::unique(visited.begin(), visited.end()), visited.end());
        }
        // Its cost per link, the meshing of the leaves it changed included;
        // a cheap bounce lowers the expectation only by degrees.
        const double took = secondsSince(began) + tail_.seconds(stats.changedLeaves - leavesBefore) - tail_.seconds(0);
        double& rate = share < 1.0 ? cutBounceSecondsPerLink_ : bounceSecondsPerLink_;
        if (links > 0) rate = std::max(took / double(links), 0.75 * rate);
    }
    // On a deadline, the push of what waits is made only in the share that
    // fits (a cluster's push re-meshes all of its members), largest changes
    // first, but in full by an idle frame that has sent everything.
    if (waiting_.empty()) return;
    const double share = idle_ && unsent_.empty() ? 1.0 : shareThatFits(stats.changedLeaves, waitingPushSeconds_);
    if (share < kLeastShare) return;
    std::vector<ElementId> pushed;
    pushed.swap(waiting_);
    if (share < 1.0)
        keepShare(
            pushed, share, [](ElementId) { return 1.0; }, [&](ElementId e) { return waitingChange_[e] * h_[e].area; },
            [&](ElementId e) { waiting_.push_back(e); });
    const auto began = std::chrono::steady_clock::now();
    const std::size_t leavesBefore = stats.changedLeaves;
    for (ElementId e : pushed) {
        waitingChange_[e] = -1.0;
        // Freed since it began waiting (a removed subdivision): nothing to push.
        if (h_.isLive(e)) refiner_.markDirty(e);
    }
    // On the clock too, by subtree (pushPull): the share is chosen by what
    // the last such push took, which misjudges one that reaches a large
    // cluster (in `office` at 60 fps, 5 to 7.5 ms where 1.5 to 2 were
    // expected); what does not fit waits, unpushed.
    visited = pushPull(stats, true);
    touch(visited);
    const double took = secondsSince(began) + tail_.seconds(stats.changedLeaves - leavesBefore) - tail_.seconds(0);
    waitingPushSeconds_ = std::max(took / share, 0.75 * waitingPushSeconds_);
    // Idle time sends what that push changed too, down to the threshold:
    // otherwise it stayed unsent until a later frame's push passed by it
    // (0.2% of the light of a room a block left and came back to, once the
    // fill kept the room's light).
    if (idle_ && stats.bounces < settings.maxBounces) bounce(std::move(visited), settings, stats);
}

void LineSpaceUpdate::applyTransfers(const std::vector<Transfer>& transfers, double threshold) {
    // In the serial order, so that every irradiance gets the same sum.
    // Bound by memory: the receivers a few transfers ahead are asked for early.
    constexpr std::size_t kAhead = 8;
    for (std::size_t k = 0; k < transfers.size(); ++k) {
        if (k + kAhead < transfers.size()) {
            const HElement& ahead = h_[transfers[k + kAhead].receiver];
            __builtin_prefetch(&ahead.irradiance);
            __builtin_prefetch(&ahead.dirty);
        }
        const Transfer& t = transfers[k];
        // Nothing arrives (a cluster source none of whose facets face the
        // receiver): the receiver neither changes nor waits to be pushed.
        if (t.irradiance == glm::dvec3(0.0)) continue;
        HElement& r = h_[t.receiver];
        if (r.isSurface()) {
            r.irradiance += t.irradiance;
            if (!h_[t.source].isSurface()) r.clusterIrradiance += t.irradiance;
        } else
            addTransfer(h_, t.receiver, t.source, t.irradiance);
        if (r.dirty) continue;
        // The most the receiver's radiosity can move (a cluster's
        // members reflect at most all of it).
        const glm::dvec3 moved =
            r.isSurface() ? glm::dvec3(r.reflectance) * t.irradiance : t.irradiance;
        if (waitingChange_.size() < h_.size()) waitingChange_.resize(h_.size(), -1.0);
        double& sum = waitingChange_[t.receiver];
        if (sum < 0.0) {
            waiting_.push_back(t.receiver);
            sum = 0.0;
        }
        sum += std::abs(luminance(moved));
        if (sum > threshold) refiner_.markDirty(t.receiver);
    }
}

bool LineSpaceUpdate::sendTransfers(const std::vector<ElementId>& visited, Thresholds threshold,
                                    BounceSeries* series, std::vector<ElementId>& held, std::size_t& sentCount) {
    // The senders and their transfers are found on all cores: reading the
    // elements and links is most of a bounce. 2: sends; 1: held.
    std::vector<char> sends(visited.size());
    // A change under `send` still goes out where it is a large share of
    // what the element sends (a dark room lit through a door), down to `hold`.
    const auto level = [&](double change, double sending, double area) {
        const double above = std::max(threshold.hold * area, std::min(threshold.send * area, threshold.share * sending));
        return change > above ? 2 : change > threshold.hold * area ? 1 : 0;
    };
    tbb::parallel_for(std::size_t(0), visited.size(), [&](std::size_t i) {
        const ElementId id = visited[i];
        const HElement& el = h_[id];
        if (el.outLinks.empty()) return;
        if (el.isSurface()) {
            sends[i] = char(level(std::abs(luminance(el.radiosity - el.gathered)), std::abs(luminance(el.radiosity)), 1.0));
            return;
        }
        // A cluster sends by facet: any facet's radiosity that moved.
        const ClusterShape& shape = h_.shape(id);
        for (int k = 0; k < shape.facetCount() && sends[i] < 2; ++k)
            if (shape.facets[k].area > 0.0)
                sends[i] = std::max(sends[i], char(level(std::abs(luminance(shape.power[k] - shape.gathered[k])),
                                                         std::abs(luminance(shape.power[k])), shape.facets[k].area)));
    });
    for (std::size_t i = 0; i < visited.size(); ++i)
        if (sends[i] == 1) held.push_back(visited[i]);
    std::vector<ElementId> sources;
    std::vector<std::size_t> first;  // per source: where its transfers start
    std::size_t count = 0;
    glm::dvec3 sent(0.0);  // the change sent, per channel: radiosity times area, or facet power
    for (std::size_t i = 0; i < visited.size(); ++i) {
        if (sends[i] != 2) continue;
        sources.push_back(visited[i]);
        first.push_back(count);
        const HElement& el = h_[visited[i]];
        count += el.outLinks.size();
        if (!series) continue;
        if (el.isSurface()) {
            sent += glm::abs(el.radiosity - el.gathered) * el.area;
        } else {
            const ClusterShape& shape = h_.shape(visited[i]);
            for (int k = 0; k < shape.facetCount(); ++k) sent += glm::abs(shape.power[k] - shape.gathered[k]);
        }
    }
    // Only a change of one bounce is a term of the series: a sender sends
    // ahead if it sent in the last bounce. What an element kept unsent over
    // several (each under the threshold) goes out once (sent ahead, such
    // sums made a moved block's bounces in the Cornell box grow).
    glm::dvec3 ahead(1.0);  // what a sender that sends ahead sends, times its change
    std::vector<char> sendsAhead(sources.size(), 0);
    if (series && !series->done) {
        const glm::dvec3 ratio = glm::all(glm::greaterThan(series->last, glm::dvec3(0.0))) ? sent / series->last : glm::dvec3(-1.0);
        bool steady = true;
        for (int c = 0; c < 3; ++c)
            steady = steady && ratio[c] >= kSmallestBounceRatio && ratio[c] <= kLargestBounceRatio && series->ratio[c] > 0.0 &&
                     std::abs(ratio[c] - series->ratio[c]) <= kSteadyBounceRatio * (1.0 - ratio[c]);
        if (steady) {
            ahead = 1.0 / (1.0 - ratio);
            series->done = true;  // what follows is the guess's correction, in plain bounces
            for (std::size_t k = 0; k < sources.size(); ++k)
                if (std::binary_search(series->lastSenders.begin(), series->lastSenders.end(), sources[k])) {
                    sendsAhead[k] = 1;
                    series->sentAhead.push_back(sources[k]);
                }
        } else {
            series->ratio = ratio;
            series->last = sent;
            series->lastSenders = sources;
            std::sort(series->lastSenders.begin(), series->lastSenders.end());
        }
    }
    // A block of senders at a time: their transfers found on all cores into
    // a buffer kept from frame to frame (transferBlock_ transfers), then
    // added in order. Into one array for the whole bounce, made for each,
    // the first frame of an edit of `office` (bounces of up to 500,000
    // transfers) wrote 16 MB of fresh memory, at a page fault per 4 KiB
    // (about 11 us here). Collecting a block does
    // not read what adding the one before wrote (the senders' radiosity
    // and gathered light, and the links; adding writes receivers'
    // irradiance): the same sums as one array.
    sentCount += count;
    const auto endOf = [&](std::size_t i) { return i < sources.size() ? first[i] : count; };
    for (std::size_t a = 0; a < sources.size();) {
        // Senders a to b - 1: at least one, and as many more as the block holds.
        std::size_t b = a + 1;
        while (b < sources.size() && endOf(b + 1) - first[a] <= transferBlock_) ++b;
        transfers_.resize(endOf(b) - first[a]);
        collectTransfers(std::span(sources).subspan(a, b - a), std::span(first).subspan(a, b - a),
                         std::span(sendsAhead).subspan(a, b - a), ahead);
        applyTransfers(transfers_, threshold.send);
        a = b;
    }
    return !sources.empty();
}

void LineSpaceUpdate::collectTransfers(std::span<const ElementId> sources, std::span<const std::size_t> first,
                                       std::span<const char> sendsAhead, const glm::dvec3& ahead) {
    const std::size_t base = first.empty() ? 0 : first[0];
    tbb::parallel_for(std::size_t(0), sources.size(), [&](std::size_t k) {
        HElement& el = h_[sources[k]];
        // In-place gather of the difference on every link leaving the source.
        const glm::dvec3 factor = sendsAhead[k] ? ahead : glm::dvec3(1.0);
        const glm::dvec3 delta = factor * (el.radiosity - el.gathered);
        ClusterShape::Powers facetDelta{};
        if (el.shape != kNone) {
            ClusterShape& shape = h_.shape(sources[k]);
            for (int f = 0; f < shape.facetCount(); ++f) {
                facetDelta[f] = factor * (shape.power[f] - shape.gathered[f]);
                shape.gathered[f] = sendsAhead[k] ? shape.gathered[f] + facetDelta[f] : shape.power[f];
            }
        }
        for (std::size_t j = 0; j < el.outLinks.size(); ++j) {
            links_.prefetchAhead(el.outLinks, j);
            const Link& l = links_[el.outLinks[j]];
            transfers_[first[k] - base + j] = Transfer{l.receiver, l.source, double(l.gathered) * sentChange(h_, l, delta, facetDelta)};
        }
        // Held exactly as sent: a thousand moves away and back must return
        // the original solution to the last bit.
        el.gathered = sendsAhead[k] ? el.gathered + delta : el.radiosity;
    });
}

void LineSpaceUpdate::followTheLight(const UpdateSettings& settings, FrameStats& stats, std::size_t budget,
                                     bool coarsen) {
    // On a deadline, stepping the oracles of what the frame touched waits
    // when it is not expected to fit (at what it last took per element
    // touched): the elements stay touched, and a later frame or idle time
    // steps them (on the building floor, after a change that reached 60,000
    // elements, stepping and judging took 8 ms).
    if (deadline_ && !idle_ &&
        shareThatFits(stats.changedLeaves, followSecondsPerElement_ * double(touched_.size())) < 1.0)
        return;
    const auto began = std::chrono::steady_clock::now();
    const std::size_t touched = touched_.size();
    SteppedOracles stepped = stepOracles(h_, touched_, kOracleFloor * referenceRadiosity_, lightScale_);
    clearTouched();
    if (touched >= kPushSample)
        followSecondsPerElement_ = std::max(secondsSince(began) / double(touched), 0.75 * followSecondsPerElement_);
    // The links an element sends are judged for refinement when its oracle
    // rose. One that fell asks for no refinement its links did not ask for
    // already (they were judged, refined, or left pending), only for
    // coarsening, below. A light of `office` dimmed by a tenth of its
    // emission a frame stepped about 1,000 elements, most of them down, and
    // judging the 60,000 to 70,000 links they send took 5 ms and refined
    // none.
    std::vector<ElementId>& moved = stepped.moved;
    std::vector<ElementId>& rose = stepped.rose;
    // What stepped in earlier frames, whose links a deadline left unjudged
    // (judged whichever way it stepped).
    if (!judgeLater_.empty()) {
        for (std::vector<ElementId>* list : {&moved, &rose}) {
            list->insert(list->end(), judgeLater_.begin(), judgeLater_.end());
            std::sort(list->begin(), list->end());
            list->erase(std::unique(list->begin(), list->end()), list->end());
        }
        judgeLater_.clear();
    }
    // Judging the links of what stepped waits too, on a deadline, when it is
    // not expected to fit (at what it last took per link): stepping costs
    // little per element, but an edit that changes the scene's power steps
    // every element, and judging all of `office`'s links took 72 ms of a
    // 17 ms frame.
    std::size_t judged = 0;
    for (ElementId s : rose) judged += h_[s].outLinks.size();
    if (deadline_ && !idle_ && shareThatFits(stats.changedLeaves, judgeSecondsPerLink_ * double(judged)) < 1.0) {
        judgeLater_ = std::move(moved);
        return;
    }
    const auto judging = std::chrono::steady_clock::now();
    // Idle time also coarsens what edits left finer than their light asks.
    std::vector<ElementId> coarser;
    if (idle_) {
        coarser.swap(coarsenLater_);
        for (ElementId e : coarser) coarsenQueued_[e] = 0;
    }
    if (moved.empty() && coarser.empty()) return;
    const auto coarsenInIdleTime = [&](ElementId e) {
        if (coarsenQueued_.size() < h_.size()) coarsenQueued_.resize(h_.size(), 0);
        if (!std::exchange(coarsenQueued_[e], 1)) coarsenLater_.push_back(e);
    };
    const std::size_t spentBefore = stats.spent;
    RefineHeap heap;
    for (ElementId s : rose) {
        if (!h_.isLive(s)) continue;  // freed since it stepped
        const IdList& out = h_[s].outLinks;
        for (std::size_t k = 0; k < out.size(); ++k) {
            links_.prefetchAhead(out, k);
            if (refiner_.wouldRefine(links_[out[k]])) heap.push({heapKey(links_[out[k]]), out[k]});
        }
    }
    for (ElementId s : moved) {
        if (!h_.isLive(s)) continue;
        // Back at the solve's level (an edit taken back), the solve's
        // hierarchy returns at once.
        if (coarsen || h_[s].level == 0) {
            coarser.push_back(s);
        } else if (!h_[s].outPlinks.empty()) {
            coarsenInIdleTime(s);
        }
    }
    // Refinement the new oracle no longer asks for goes (its line-space
    // children with it). An element queued for idle time may have been
    // freed since (its id given to another): judged as it is now.
    std::sort(coarser.begin(), coarser.end());
    coarser.erase(std::unique(coarser.begin(), coarser.end()), coarser.end());
    if (judged >= kPushSample)
        judgeSecondsPerLink_ = std::max(secondsSince(judging) / double(judged), 0.75 * judgeSecondsPerLink_);
    // On a deadline, coarsening waits for idle time when it is not expected
    // to fit (at what it last took per p-link looked at; before any, at
    // kCoarsenGuess): an object moving back over where it stood at the
    // solve returns elements to the solve's level by the hundred, and
    // reinstating the p-links of one frame's took 11 ms past a random
    // room's deadline at 60 fps.
    std::size_t plinks = 0;
    for (ElementId s : coarser)
        if (h_.isLive(s)) plinks += h_[s].outPlinks.size();
    const double perPlink = coarsenSecondsPerPlink_ > 0.0 ? coarsenSecondsPerPlink_ : kCoarsenGuess;
    if (deadline_ && !idle_ && shareThatFits(stats.changedLeaves, perPlink * double(plinks)) < 1.0) {
        for (ElementId s : coarser)
            if (h_.isLive(s)) coarsenInIdleTime(s);
        coarser.clear();
        plinks = 0;
    }
    const auto coarsening = std::chrono::steady_clock::now();
    for (ElementId s : coarser) {
        if (!h_.isLive(s)) continue;
        for (LinkId id : IdList(h_[s].outPlinks)) {
            const Link& l = links_[id];
            if (l.live && l.passive && l.source == s && !refiner_.wouldRefine(l)) {
                reinstate(id);
                ++stats.reinstated;
                ++stats.spent;
            }
        }
    }
    if (plinks >= kPushSample)
        coarsenSecondsPerPlink_ = std::max(secondsSince(coarsening) / double(plinks), 0.75 * coarsenSecondsPerPlink_);
    const std::size_t used = stats.spent - spentBefore;
    refineFromHeap(heap, stats, budget == kUnlimited ? kUnlimited : (budget > used ? budget - used : 0));
    // The light that the new links carry, once around.
    std::vector<ElementId> visited = pushPull(stats, true);
    bounce(std::move(visited), settings, stats);
    clearTouched();  // what moved now is stepped at the next frame
}

}  // namespace rad
