#include "core/FramePipeline.h"

#include <climits>
#include <deque>
#include <exception>
#include <mutex>
#include <utility>

#include <tbb/task_arena.h>
#include <tbb/task_group.h>

namespace cg {

namespace {

/// One frame in flight.
struct Frame {
    int frame = 0;
    FramePipeline::FrameOutputs results;
    std::vector<char> member;  ///< cooked at this frame
    std::vector<char> done;
    std::vector<int> waiting;  ///< inputs at this frame, and the node at the frame before, not done
    std::size_t left = 0;      ///< members not done
};

using Ready = std::vector<std::pair<Frame*, std::size_t>>;

}  // namespace

FramePipeline::FramePipeline(const std::vector<std::vector<std::size_t>>& upstream, int window,
                             std::vector<bool> anyOrder)
    : mUpstream(upstream),
      mDownstream(upstream.size()),
      mInOrder(upstream.size(), true),
      mWindow(window < 1 ? 1 : window)
{
    for (std::size_t i = 0; i < anyOrder.size() && i < upstream.size(); ++i)
        mInOrder[i] = !anyOrder[i];
    for (std::size_t i = 0; i < upstream.size(); ++i)
        for (std::size_t up : upstream[i]) mDownstream[up].push_back(i);
}

void FramePipeline::run(int first, int last, const Plan& plan, const Cook& cook, const Done& done)
{
    const std::size_t n = mUpstream.size();
    std::mutex mutex;                           // guards everything below but the cooks themselves
    std::deque<std::unique_ptr<Frame>> flight;  // oldest first, consecutive frames
    std::exception_ptr error;                   // of the earliest frame that failed
    int failedAt = INT_MAX;                     // that frame; frames before it still finish
    bool admitting = false;
    int next = first;
    tbb::task_group tasks;

    // Frames whose nodes are all done leave in order; the caller hears of each.
    const auto finishFrames = [&] {
        while (!flight.empty() && flight.front()->left == 0) {
            done(flight.front()->frame, flight.front()->results);
            flight.pop_front();
        }
    };
    const auto successor = [&](const Frame& fr) -> Frame* {
        for (std::size_t k = 0; k + 1 < flight.size(); ++k)
            if (flight[k].get() == &fr) return flight[k + 1].get();
        return nullptr;
    };

    std::function<void(const Ready&)> spawn;
    std::function<void()> admit;

    const auto finished = [&](Frame& fr, std::size_t idx, OutputsPtr out) {
        Ready ready;
        {
            std::lock_guard<std::mutex> lock(mutex);
            fr.results[idx] = std::move(out);
            fr.done[idx] = 1;
            --fr.left;
            for (std::size_t down : mDownstream[idx])
                if (fr.member[down] && --fr.waiting[down] == 0) ready.emplace_back(&fr, down);
            if (Frame* later = mInOrder[idx] ? successor(fr) : nullptr)
                if (later->member[idx] && --later->waiting[idx] == 0)
                    ready.emplace_back(later, idx);
            finishFrames();
        }
        spawn(ready);
        admit();
    };
    // The first failure at a frame: nothing at or after it starts any more.
    const auto fail = [&](int frame) {
        std::lock_guard<std::mutex> lock(mutex);
        if (frame < failedAt) {
            failedAt = frame;
            error = std::current_exception();
        }
    };

    spawn = [&](const Ready& ready) {
        for (const auto& [frame, idx] : ready) {
            Frame* fr = frame;
            const std::size_t node = idx;
            tasks.run([&, fr, node] {
                {
                    std::lock_guard<std::mutex> lock(mutex);
                    if (fr->frame >= failedAt) return;
                }
                OutputsPtr out;
                try {
                    // Isolated: while this cook waits inside its own parallel loops, its
                    // thread takes none of another node's cook onto its stack.
                    tbb::this_task_arena::isolate(
                        [&] { out = cook(node, fr->frame, fr->results); });
                } catch (...) {
                    fail(fr->frame);
                    return;
                }
                finished(*fr, node, std::move(out));
            });
        }
    };

    // Starts frames while the window has room, one admitting thread at a time, in order.
    admit = [&] {
        {
            std::lock_guard<std::mutex> lock(mutex);
            if (admitting) return;
            admitting = true;
        }
        for (;;) {
            int frame = 0;
            {
                std::lock_guard<std::mutex> lock(mutex);
                if (failedAt != INT_MAX || next > last ||
                    flight.size() >= static_cast<std::size_t>(mWindow)) {
                    admitting = false;
                    return;
                }
                frame = next++;
            }
            auto fr = std::make_unique<Frame>();
            fr->frame = frame;
            fr->results.assign(n, nullptr);
            std::vector<std::size_t> nodes;
            try {
                nodes = plan(frame, fr->results);
            } catch (...) {
                fail(frame);
                std::lock_guard<std::mutex> lock(mutex);
                admitting = false;
                return;
            }
            Ready ready;
            {
                std::lock_guard<std::mutex> lock(mutex);
                fr->member.assign(n, 0);
                fr->done.assign(n, 0);
                fr->waiting.assign(n, 0);
                for (std::size_t idx : nodes) fr->member[idx] = 1;
                const Frame* before = flight.empty() ? nullptr : flight.back().get();
                for (std::size_t idx : nodes) {
                    int wait = 0;
                    for (std::size_t up : mUpstream[idx]) wait += fr->member[up];
                    if (before && mInOrder[idx] && before->member[idx] && !before->done[idx])
                        ++wait;
                    fr->waiting[idx] = wait;
                    if (wait == 0) ready.emplace_back(fr.get(), idx);
                }
                fr->left = nodes.size();
                flight.push_back(std::move(fr));
                finishFrames();
            }
            spawn(ready);
        }
    };

    admit();
    tasks.wait();
    if (error) std::rethrow_exception(error);
}

}  // namespace cg
