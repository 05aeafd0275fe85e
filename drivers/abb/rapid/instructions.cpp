#include "drivers/abb/rapid/instructions.hpp"

#include "drivers/abb/rapid/names.hpp"

namespace fibrecell::drivers::abb::rapid {
namespace {

using P = std::string_view;
using O = OptionalParam;

// Positional parameter lists.
constexpr std::span<const P> p_none{};
constexpr P p_move[] = {"robtarget", "speeddata", "zonedata", "tooldata"};
constexpr P p_movec[] = {"robtarget", "robtarget", "speeddata", "zonedata", "tooldata"};
constexpr P p_moveabsj[] = {"jointtarget", "speeddata", "zonedata", "tooldata"};
constexpr P p_moveldo[] = {"robtarget", "speeddata", "zonedata", "tooldata", "signaldo", "num"};
constexpr P p_trigg_move[] = {"robtarget", "speeddata", "triggdata", "zonedata", "tooldata"};
constexpr P p_triggio[] = {"triggdata", "num", "num"};
constexpr P p_triggequip[] = {"triggdata", "num", "num", "num"};
constexpr P p_triggint[] = {"triggdata", "num", "intnum"};
constexpr P p_triggspeed[] = {"triggdata", "num", "num", "signalao", "num"};
constexpr P p_setdo[] = {"signaldo", "num"};
constexpr P p_setgo[] = {"signalgo", "num"};
constexpr P p_setao[] = {"signalao", "num"};
constexpr P p_signaldo[] = {"signaldo"};
constexpr P p_waitdi[] = {"signaldi", "num"};
constexpr P p_waitgi[] = {"signalgi", "num"};
constexpr P p_bool[] = {"bool"};
constexpr P p_num[] = {"num"};
constexpr P p_num2[] = {"num", "num"};
constexpr P p_string[] = {"string"};
constexpr P p_string2[] = {"string", "string"};
constexpr P p_startload[] = {"string", "loadsession"};
constexpr P p_loadsession[] = {"loadsession"};
constexpr P p_intnum[] = {"intnum"};
constexpr P p_isignal_di[] = {"signaldi", "num", "intnum"};
constexpr P p_isignal_gi[] = {"signalgi", "intnum"};  // any change of the group
constexpr P p_isignal_do[] = {"signaldo", "num", "intnum"};
constexpr P p_itimer[] = {"num", "intnum"};
constexpr P p_clock[] = {"clock"};
constexpr P p_loaddata[] = {"loaddata"};

// Optional arguments and switches.
constexpr std::span<const O> o_none{};
constexpr O o_movel[] = {{"Conc", ""},         {"ID", "any"}, {"V", "num"},
                         {"T", "num"},         {"Z", "num"},  {"Inpos", "any"},
                         {"WObj", "wobjdata"}, {"Corr", ""},  {"TLoad", "loaddata"}};
constexpr O o_movej[] = {{"Conc", ""},         {"ID", "any"},        {"V", "num"},
                         {"T", "num"},         {"Z", "num"},         {"Inpos", "any"},
                         {"WObj", "wobjdata"}, {"TLoad", "loaddata"}};
constexpr O o_moveabsj[] = {{"Conc", ""},     {"ID", "any"},        {"NoEOffs", ""},
                            {"V", "num"},     {"T", "num"},         {"Z", "num"},
                            {"Inpos", "any"}, {"WObj", "wobjdata"}, {"TLoad", "loaddata"}};
constexpr O o_moveldo[] = {{"T", "num"}, {"WObj", "wobjdata"}, {"TLoad", "loaddata"}};
constexpr O o_triggl[] = {{"Conc", ""},        {"ID", "any"},        {"T", "num"},
                          {"T2", "triggdata"}, {"T3", "triggdata"},  {"T4", "triggdata"},
                          {"T5", "triggdata"}, {"T6", "triggdata"},  {"T7", "triggdata"},
                          {"T8", "triggdata"}, {"Inpos", "any"},     {"WObj", "wobjdata"},
                          {"Corr", ""},        {"TLoad", "loaddata"}};
constexpr O o_triggj[] = {{"Conc", ""},         {"ID", "any"},       {"T", "num"},
                          {"T2", "triggdata"},  {"T3", "triggdata"}, {"T4", "triggdata"},
                          {"T5", "triggdata"},  {"T6", "triggdata"}, {"T7", "triggdata"},
                          {"T8", "triggdata"},  {"Inpos", "any"},    {"WObj", "wobjdata"},
                          {"TLoad", "loaddata"}};
constexpr O o_triggio[] = {{"Start", ""},       {"Time", ""},        {"DOp", "signaldo"},
                           {"GOp", "signalgo"}, {"AOp", "signalao"}, {"ProcID", "num"},
                           {"DODelay", "num"}};
constexpr O o_triggequip[] = {{"Start", ""},       {"DOp", "signaldo"}, {"GOp", "signalgo"},
                              {"AOp", "signalao"}, {"ProcID", "num"},   {"Inhib", "any"}};
constexpr O o_triggint[] = {{"Start", ""}, {"Time", ""}};
constexpr O o_triggspeed[] = {
    {"Start", ""}, {"DipLag", "num"}, {"ErrDO", "signaldo"}, {"Inhib", "any"}};
constexpr O o_setdo[] = {{"SDelay", "num"}, {"Sync", ""}};
constexpr O o_setgo[] = {{"SDelay", "num"}};
constexpr O o_pulsedo[] = {{"High", ""}, {"PLength", "num"}};
constexpr O o_waitdi[] = {{"MaxTime", "num"}, {"TimeFlag", "bool"}};
constexpr O o_waitgi[] = {
    {"NOTEQ", ""}, {"LT", ""}, {"GT", ""}, {"MaxTime", "num"}, {"TimeFlag", "bool"}};
constexpr O o_waituntil[] = {
    {"InPos", ""}, {"MaxTime", "num"}, {"TimeFlag", "bool"}, {"PollRate", "num"}};
constexpr O o_inpos[] = {{"InPos", ""}};
constexpr O o_waitrob[] = {{"InPos", ""}, {"ZeroSpeed", ""}};
constexpr O o_onoff[] = {{"On", ""}, {"Off", ""}};
constexpr O o_singarea[] = {{"Wrist", ""}, {"LockAxis4", ""}, {"Off", ""}};
constexpr O o_tpwrite[] = {
    {"Num", "num"}, {"Bool", "bool"}, {"Pos", "pos"}, {"Orient", "orient"}, {"Dnum", "dnum"}};
constexpr O o_errwrite[] = {
    {"W", ""}, {"I", ""}, {"RL2", "string"}, {"RL3", "string"}, {"RL4", "string"}};
constexpr O o_stop[] = {{"NoRegain", ""}, {"AllMoveTasks", ""}};
constexpr O o_stopmove[] = {{"Quick", ""}, {"AllMotionTasks", ""}};
constexpr O o_startmove[] = {{"AllMotionTasks", ""}};
constexpr O o_load[] = {{"Dynamic", ""}, {"File", "string"}, {"CheckRef", ""}};
constexpr O o_startload[] = {{"Dynamic", ""}, {"File", "string"}};
constexpr O o_waitload[] = {{"UnloadPath", "string"}, {"UnloadFile", "string"}, {"CheckRef", ""}};
constexpr O o_unload[] = {{"ErrIfChanged", ""}, {"Save", ""}, {"File", "string"}};
constexpr O o_accset[] = {{"FinePointRamp", "num"}};
constexpr O o_isignal[] = {{"Single", ""}, {"SingleSafe", ""}};

constexpr MoveRoles no_move{};
constexpr MoveRoles move_roles{.target = 0, .speed = 1, .zone = 2, .tool = 3};
constexpr MoveRoles movec_roles{.target = 1, .via = 0, .speed = 2, .zone = 3, .tool = 4};
constexpr MoveRoles trigg_roles{.target = 0, .speed = 1, .zone = 3, .tool = 4, .trigger = 2};

const InstructionInfo instructions[] = {
    {"MoveL", p_move, o_movel, move_roles},
    {"MoveJ", p_move, o_movej, move_roles},
    {"MoveC", p_movec, o_movel, movec_roles},
    {"MoveAbsJ", p_moveabsj, o_moveabsj, move_roles},
    {"MoveLDO", p_moveldo, o_moveldo, move_roles},
    {"TriggL", p_trigg_move, o_triggl, trigg_roles},
    {"TriggJ", p_trigg_move, o_triggj, trigg_roles},
    {"TriggIO", p_triggio, o_triggio, no_move, true},
    {"TriggEquip", p_triggequip, o_triggequip, no_move, true},
    {"TriggInt", p_triggint, o_triggint, no_move, true},
    {"TriggSpeed", p_triggspeed, o_triggspeed, no_move, true},
    {"SetDO", p_setdo, o_setdo, no_move},
    {"SetGO", p_setgo, o_setgo, no_move},
    {"SetAO", p_setao, o_none, no_move},
    {"Set", p_signaldo, o_none, no_move},
    {"Reset", p_signaldo, o_none, no_move},
    {"PulseDO", p_signaldo, o_pulsedo, no_move},
    {"WaitDI", p_waitdi, o_waitdi, no_move},
    {"WaitDO", p_setdo, o_waitdi, no_move},
    {"WaitGI", p_waitgi, o_waitgi, no_move},
    {"WaitUntil", p_bool, o_waituntil, no_move},
    {"WaitTime", p_num, o_inpos, no_move},
    {"WaitRob", p_none, o_waitrob, no_move},
    {"ConfL", p_none, o_onoff, no_move},
    {"ConfJ", p_none, o_onoff, no_move},
    {"SingArea", p_none, o_singarea, no_move},
    {"TPWrite", p_string, o_tpwrite, no_move},
    {"TPErase", p_none, o_none, no_move},
    {"ErrWrite", p_string2, o_errwrite, no_move},
    {"Stop", p_none, o_stop, no_move},
    {"StopMove", p_none, o_stopmove, no_move},
    {"StartMove", p_none, o_startmove, no_move},
    {"ClearPath", p_none, o_none, no_move},
    {"ExitCycle", p_none, o_none, no_move},
    {"Break", p_none, o_none, no_move},
    {"Load", p_string, o_load, no_move},
    {"StartLoad", p_startload, o_startload, no_move},
    {"WaitLoad", p_loadsession, o_waitload, no_move},
    {"UnLoad", p_string, o_unload, no_move},
    {"Incr", p_num, o_none, no_move},
    {"Decr", p_num, o_none, no_move},
    {"Add", p_num2, o_none, no_move},
    {"Clear", p_num, o_none, no_move},
    {"AccSet", p_num2, o_accset, no_move},
    {"VelSet", p_num2, o_none, no_move},
    {"IDelete", p_intnum, o_none, no_move},
    {"ISignalDI", p_isignal_di, o_isignal, no_move},
    {"ISignalGI", p_isignal_gi, o_isignal, no_move},
    {"ISignalDO", p_isignal_do, o_isignal, no_move},
    {"ITimer", p_itimer, o_isignal, no_move},
    {"ISleep", p_intnum, o_none, no_move},
    {"IWatch", p_intnum, o_none, no_move},
    {"IEnable", p_none, o_none, no_move},
    {"IDisable", p_none, o_none, no_move},
    {"ClkReset", p_clock, o_none, no_move},
    {"ClkStart", p_clock, o_none, no_move},
    {"ClkStop", p_clock, o_none, no_move},
    {"GripLoad", p_loaddata, o_none, no_move},
};

}  // namespace

const InstructionInfo* find_instruction(std::string_view name) {
    for (const InstructionInfo& i : instructions)
        if (same_name(i.name, name)) return &i;
    return nullptr;
}

bool is_builtin_instruction(std::string_view name) {
    return find_instruction(name) != nullptr;
}

bool is_extra_trigger(std::string_view optional_name) {
    return optional_name.size() == 2 && (optional_name[0] == 'T' || optional_name[0] == 't') &&
           optional_name[1] >= '2' && optional_name[1] <= '8';
}

}  // namespace fibrecell::drivers::abb::rapid
