#pragma once
// CPU priorities of the cell's threads. The threads that keep the robot and the extruder in step
// (sync engine, serial I/O to the board, Modbus polling of the robot's I/O) must run ahead of
// everything else on the machine: a planning job, a compiler, a browser. They ask for the
// real-time policy SCHED_FIFO where permitted (root, CAP_SYS_NICE, or the unit's LimitRTPRIO);
// where it is not they stay at nice 0, ahead of planning at nice 10 (jobs.planner_nice) only.
// All of them block on I/O or a timer almost all the time, so a real-time priority costs the
// rest of the machine nothing; the kernel's real-time throttling still bounds a runaway thread.
//
//   set_time_critical_priority(20);          // once, from the cell config (print.realtime_priority)
//   std::thread([] { make_thread_time_critical("marlin.io"); io.run(); });
//
// The simulated devices (mock board, simulated controller) call it too: they stand in for
// hardware with a processor of its own, so a loaded host must not show up as device latency.

#include <string_view>

namespace fibrecell::config {

// The SCHED_FIFO priority (1..99) time-critical threads ask for; 0 keeps them at the normal
// policy. Process-wide; 20 until set: above kernel threads' defaults of 1, below the 50 of IRQ
// threads on a PREEMPT_RT kernel.
void set_time_critical_priority(int priority);
int time_critical_priority();

// Names the calling thread (its first 15 characters): what ps -L, top -H and
// /proc/<pid>/task/*/comm show, and what docs/service.md's list of threads calls it.
void name_this_thread(std::string_view name);

// Names the calling thread `thread` (name_this_thread) and puts it at the
// time-critical priority. Logs once per process when the real-time policy is refused, and why;
// never throws.
void make_thread_time_critical(std::string_view thread);

// Lowers the calling thread's priority to `nice` (Linux keeps one per thread and copies it to
// the threads it starts). Never raises it; logs when it cannot.
void lower_thread_priority(int nice);

}  // namespace fibrecell::config
