#pragma once
// What the firmware took of each extruder's filament, counted from the lines it acknowledged and
// read as Marlin reads them: T<n> selects the extruder, M82/M83 make E absolute/relative, G92 E
// sets the position, G0-G3 with an E word move it. Net millimetres: a retraction counts back.
// Spools and the job history are charged from it (docs/history.md), so what they say is what the
// board did, not what the plan meant.

#include <array>
#include <string_view>

namespace fibrecell::drivers::marlin {

// Millimetres of filament per extruder, E0 first.
struct FeedTotals {
    static constexpr int extruders = 8;  // Marlin's most
    std::array<double, extruders> mm{};

    double of(int extruder) const {
        return extruder >= 0 && extruder < extruders ? mm[static_cast<std::size_t>(extruder)] : 0.0;
    }
};

class FeedLedger {
  public:
    // Whether `command` (comment stripped) changes what the ledger counts or how it reads E.
    static bool counts(std::string_view command);

    // An acknowledged command, in the order the firmware executed them. `e_ran` false: the
    // firmware dropped its E part (`cold extrusion prevented`), the position moved all the same.
    void taken(std::string_view command, bool e_ran = true);
    // The firmware (re)started: extruder 0, absolute E at 0, as Marlin boots. Totals stay.
    void firmware_started();

    const FeedTotals& totals() const { return totals_; }

  private:
    FeedTotals totals_;
    int extruder_ = 0;
    bool relative_ = false;
    double position_ = 0;  // the current extruder's E, for absolute moves
};

}  // namespace fibrecell::drivers::marlin
