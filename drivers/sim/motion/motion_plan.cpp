#include "drivers/sim/motion/motion_plan.hpp"

#include "drivers/abb/kinematics/opw_kinematics.hpp"

#include <algorithm>
#include <cmath>

namespace fibrecell::drivers::sim {
namespace {

// Path positions this close count as the same point (a stop exactly at a stop point).
constexpr double same_point_mm = 1e-6;

}  // namespace

MotionPlan::MotionPlan(const SimClock& clock, const MotionOptions& options, double t_s)
    : clock_(clock),
      options_(options),
      robot_(abb::irb1200(options.variant)),
      t_(t_s),
      recorder_(options.max_samples) {
    tail_.joints = options.start_joints;
    tail_.tcp = abb::forward_kinematics(robot_.geometry, options.start_joints);
}

std::uint64_t MotionPlan::append(const MotionSegment& move) {
    settle();
    PathSegment seg = solve_segment(move, tail_, robot_, options_.solver);
    const std::uint64_t id = seg.id = next_id_++;
    tail_ = seg.pose_at(1);
    queue_.push_back(std::move(seg));
    replan();
    return id;
}

void MotionPlan::stop() {
    settle();
    stopped_ = true;
    ++changes_;
    if (stop_at_mm_) return;
    stop_at_mm_ = standstill_position();
    replan();
}

void MotionPlan::resume() {
    settle();
    if (!stopped_) return;
    stopped_ = false;
    stop_at_mm_.reset();
    ++changes_;
    replan();
}

void MotionPlan::clear() {
    settle();
    for (PathSegment& seg : queue_) {
        seg.triggers.clear();
        seg.cleared = true;
    }
    triggers_.clear();
    ++changes_;
    if (!active()) {
        tail_ = pose_now();
        queue_.clear();
        where_ = {};
        return;
    }
    stop();
    // Keep what the robot brakes along, ending where it will stand.
    const double stop_mm = *stop_at_mm_;
    while (queue_.size() > 1 && queue_.back().path_start_mm >= stop_mm - same_point_mm)
        queue_.pop_back();
    queue_.back().truncate(stop_mm - queue_.back().path_start_mm);
    tail_ = queue_.back().pose_at(1);
    replan();
}

void MotionPlan::halt() {
    settle();
    const bool was_active = active();
    tail_ = pose_now();
    queue_.clear();
    triggers_.clear();
    profile_ = {};
    where_ = {};
    if (stopped_) stop_at_mm_ = tail_.path_mm;
    if (was_active) recorder_.record(sample(tail_, 0, t_));
    ++changes_;
}

void MotionPlan::idle_until(double t_s) {
    if (!active() && t_s > t_) t_ = t_s;
}

std::vector<std::function<void()>> MotionPlan::advance_to(double t_s) {
    settle();
    if (!active()) {
        idle_until(t_s);
        return {};
    }
    t_s = std::max(t_s, t_);
    record_until(t_s);
    t_ = t_s;
    unsettled_ = true;
    return triggers_.take_due(t_s, queue_);
}

void MotionPlan::settle() {
    if (!unsettled_) return;
    unsettled_ = false;
    finish_segments();
    if (t_ >= profile_.end_time()) {
        standstill();
    } else {
        where_ = profile_.at(t_);
    }
}

std::size_t MotionPlan::pending() const {
    return static_cast<std::size_t>(std::count_if(queue_.begin(), queue_.end(),
                                                  [](const PathSegment& s) { return !s.cleared; }));
}

bool MotionPlan::done(std::uint64_t id) const {
    if (id == 0 || id >= next_id_) return false;
    for (const PathSegment& seg : queue_)
        if (!seg.cleared) return id < seg.id;  // ids ascend along the queue
    return true;
}

// Highest speed at the junction after queue_[i]: a stop point, a reorientation, a tool change
// or the end of the queue stop; a fly-by point is passed at the slower segment's speed,
// reduced by the corner angle.
double MotionPlan::junction_cap(std::size_t i) const {
    if (i + 1 >= queue_.size()) return 0;
    const PathSegment& a = queue_[i];
    const PathSegment& b = queue_[i + 1];
    if (a.stop_point || !(a.length_mm > 0) || !(b.length_mm > 0) || !a.tool.isApprox(b.tool))
        return 0;
    const Eigen::Vector3d da = (a.end_mm - a.start_mm) / a.length_mm;
    const Eigen::Vector3d db = (b.end_mm - b.start_mm) / b.length_mm;
    const double corner = std::acos(std::clamp(da.dot(db), -1.0, 1.0));
    return std::min(a.cruise_mm_s, b.cruise_mm_s) * corner_speed_factor(corner);
}

// Path position [mm] where braking now at the set acceleration ends, or the planned standstill
// ahead (a stop point the robot already brakes for) when that is nearer.
double MotionPlan::standstill_position() const {
    const double here = pose_now().path_mm;
    if (!active()) return here;
    const double v = where_.speed_mm_s;
    double stop_mm = here + v * v / (2 * options_.accel_mm_s2);
    for (std::size_t k = profile_offset_; k < profile_.segment_count(); ++k) {
        const PathSegment& seg = queue_[k - profile_offset_];
        if (seg.path_start_mm > stop_mm) break;
        const ProfilePoint end = profile_.segment_end(k);
        if (end.speed_mm_s > 0) continue;
        const double end_mm = seg.path_start_mm + (seg.reorientation() ? 0 : end.position_mm);
        if (end_mm <= stop_mm + same_point_mm) stop_mm = end_mm;
        break;
    }
    return stop_mm;
}

TrajectorySample MotionPlan::current() const {
    return active() ? sample_at(t_) : sample(pose_now(), 0, t_);
}

RobotPose MotionPlan::pose_now() const {
    if (queue_.empty()) return tail_;
    const PathSegment& front = queue_.front();
    return front.pose_at(front.fraction(where_.position_mm, where_.dwell_elapsed_s));
}

TrajectorySample MotionPlan::sample(const RobotPose& pose, double speed_mm_s, double t_s) const {
    TrajectorySample s;
    s.t_s = t_s;
    s.wall = clock_.wall_at(t_s);
    s.tcp_base_mm = pose.tcp.translation();
    s.tcp_wobj_mm = pose.wobj.inverse(Eigen::Isometry) * s.tcp_base_mm;
    s.path_mm = pose.path_mm;
    s.speed_mm_s = speed_mm_s;
    s.segment = pose.segment;
    s.joints = pose.joints;
    s.source = pose.source;
    return s;
}

// The robot at `t_s` within the profile (the segment it is on not finished yet).
TrajectorySample MotionPlan::sample_at(double t_s) const {
    const ProfilePoint p = profile_.at(t_s);
    const PathSegment& seg = queue_[std::max(p.segment, profile_offset_) - profile_offset_];
    return sample(seg.pose_at(seg.fraction(p.position_mm, p.dwell_elapsed_s)), p.speed_mm_s, t_s);
}

// The robot as it leaves planned segment `planned` (its end, or the stop on a cut one).
TrajectorySample MotionPlan::sample_at_end(std::size_t planned) const {
    const ProfilePoint p = profile_.segment_end(planned);
    const PathSegment& seg = queue_[planned - profile_offset_];
    return sample(seg.pose_at(seg.fraction(p.position_mm, p.dwell_elapsed_s)), p.speed_mm_s,
                  profile_.segment_end_time(planned));
}

void MotionPlan::replan() {
    const bool was_active = active();
    std::vector<ProfileSegment> chain;
    profile_cut_ = false;
    for (std::size_t i = 0; i < queue_.size(); ++i) {
        const PathSegment& seg = queue_[i];
        const double s_in = i == 0 ? where_.position_mm : 0;
        ProfileSegment p{.length_mm = seg.length_mm,
                         .cruise_mm_s = seg.cruise_mm_s,
                         .dwell_s = seg.dwell_s,
                         .exit_cap_mm_s = junction_cap(i)};
        if (stop_at_mm_) {
            // A reorientation under way is completed; nothing else starts at or past the stop.
            const bool turning = i == 0 && seg.reorientation() && where_.dwell_elapsed_s > 0;
            if (!turning && seg.path_start_mm + s_in >= *stop_at_mm_ - same_point_mm) break;
            if (!seg.reorientation() && seg.path_end_mm() > *stop_at_mm_ + same_point_mm) {
                p.length_mm = *stop_at_mm_ - seg.path_start_mm;
                chain.push_back(p);
                profile_cut_ = true;
                break;
            }
        }
        chain.push_back(p);
    }
    profile_ = SpeedProfile(chain,
                            {.t_s = t_,
                             .position_mm = where_.position_mm,
                             .speed_mm_s = where_.speed_mm_s,
                             .dwell_elapsed_s = where_.dwell_elapsed_s},
                            options_.accel_mm_s2);
    profile_offset_ = 0;
    triggers_.plan(queue_, profile_, t_, where_.position_mm, stop_at_mm_);
    if (was_active == active()) return;
    // Starting from or coming to a standstill right here: a sample of it.
    recorder_.record(sample(pose_now(), 0, t_));
    if (active()) {
        motion_start_t_ = t_;
        records_done_ = 0;
    }
    ++changes_;
}

// Samples every record period and at every segment end in (t_, t_s], in time order, none past
// the profile's end: a thread that catches up late records the standstill at its analytic time,
// not the tick that noticed it.
void MotionPlan::record_until(double t_s) {
    t_s = std::min(t_s, profile_.end_time());
    const double period = options_.record_period_s;
    auto periodic_time = [&] {
        return period > 0 ? motion_start_t_ + static_cast<double>(records_done_ + 1) * period : t_s;
    };
    bool periodic_left = period > 0 ? periodic_time() <= t_s : true;
    std::size_t k = profile_offset_;
    while (true) {
        const bool end_left = k < profile_.segment_count() && profile_.segment_end_time(k) <= t_s;
        if (!periodic_left && !end_left) break;
        if (periodic_left && (!end_left || periodic_time() <= profile_.segment_end_time(k))) {
            recorder_.record(sample_at(periodic_time()));
            ++records_done_;
            periodic_left = period > 0 && periodic_time() <= t_s;
        } else {
            recorder_.record(sample_at_end(k++));
        }
    }
}

// Pops the segments the robot has passed the end of (or stands at).
void MotionPlan::finish_segments() {
    const std::size_t planned = profile_.segment_count();
    while (!queue_.empty() && profile_offset_ < planned) {
        const bool cut = profile_cut_ && profile_offset_ + 1 == planned;
        if (cut || profile_.segment_end_time(profile_offset_) > t_) break;
        if (!queue_.front().cleared) last_done_ = queue_.front().id;
        queue_.pop_front();
        ++profile_offset_;
        ++changes_;
    }
}

// The profile ran out: the robot stands at its end (a stop mid-segment, or the end of what is
// planned); what ClearPath left to brake along is dropped now.
void MotionPlan::standstill() {
    where_ = profile_cut_ ? profile_.segment_end(profile_.segment_count() - 1) : ProfilePoint{};
    where_.speed_mm_s = 0;
    while (!queue_.empty() && queue_.front().cleared) {
        queue_.pop_front();
        where_ = {};
    }
    profile_ = {};
    profile_cut_ = false;
    triggers_.clear();
    ++changes_;
}

}  // namespace fibrecell::drivers::sim
