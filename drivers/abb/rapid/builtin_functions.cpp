#include "drivers/abb/rapid/builtin_functions.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include <Eigen/Geometry>

#include "drivers/abb/rapid/evaluate.hpp"
#include "drivers/abb/rapid/names.hpp"
#include "drivers/abb/rapid/robot_data.hpp"

namespace fibrecell::drivers::abb::rapid {
namespace {

constexpr double deg = std::numbers::pi / 180.0;

constexpr std::string_view pure[] = {
    "abs",       "sqrt",   "exp",     "pow",      "sin",   "cos",      "tan",       "asin",
    "acos",      "atan",   "atan2",   "round",    "trunc", "numtostr", "dnumtostr", "dnumtonum",
    "numtodnum", "strlen", "strpart", "valtostr", "offs",  "orientzyx"};

class Call {
  public:
    Call(std::string_view name, const BuiltinArgs& args, std::size_t line)
        : name_(name), args_(args), line_(line) {}

    [[noreturn]] void fail(const std::string& why) const {
        throw EvalError(line_, std::string(name_) + ": " + why);
    }

    void arity(std::size_t n) const {
        if (args_.positional.size() != n)
            fail("expects " + std::to_string(n) + " arguments, found " +
                 std::to_string(args_.positional.size()));
    }

    double num(std::size_t i) const {
        const Value& v = args_.positional[i];
        if (!v.is_num()) fail("argument " + std::to_string(i + 1) + " must be a num");
        return v.num();
    }

    const std::string& str(std::size_t i) const {
        const Value& v = args_.positional[i];
        if (!v.is_string()) fail("argument " + std::to_string(i + 1) + " must be a string");
        return v.string();
    }

    const Value& value(std::size_t i) const { return args_.positional[i]; }

    const NamedValue* option(std::string_view n) const {
        for (const NamedValue& o : args_.optional)
            if (same_name(o.name, n)) return &o;
        return nullptr;
    }

    // A small non-negative integer argument (decimals, positions).
    int small_int(double v, int lo, int hi) const {
        if (!std::isfinite(v) || v != std::trunc(v) || v < lo || v > hi)
            fail("integer between " + std::to_string(lo) + " and " + std::to_string(hi) +
                 " expected, found " + format_num(v));
        return static_cast<int>(v);
    }

    int decimals() const {
        const NamedValue* dec = option("Dec");
        if (dec == nullptr) return 0;
        if (!dec->value || !dec->value->is_num()) fail("\\Dec must be a num");
        return small_int(dec->value->num(), 0, 15);
    }

    double checked(double v) const {
        if (!std::isfinite(v)) fail("result is not a finite number");
        return v;
    }

  private:
    std::string_view name_;
    const BuiltinArgs& args_;
    std::size_t line_;
};

std::string fixed(double v, int decimals, bool exponent) {
    char buf[400];  // %.15f of 1e308 fits
    std::snprintf(buf, sizeof buf, exponent ? "%.*E" : "%.*f", decimals, v);
    return buf;
}

}  // namespace

bool is_pure_builtin(std::string_view function) {
    const std::string key = fold(function);
    for (std::string_view p : pure)
        if (p == key) return true;
    return false;
}

Value call_builtin(std::string_view name, const BuiltinArgs& args, std::size_t line) {
    const Call c(name, args, line);
    const std::string f = fold(name);
    auto unary_num = [&](double (*fn)(double)) {
        c.arity(1);
        return num_value(c.checked(fn(c.num(0))));
    };
    if (f == "abs") return unary_num([](double x) { return std::fabs(x); });
    if (f == "sqrt") {
        c.arity(1);
        if (c.num(0) < 0) c.fail("negative argument");
        return num_value(std::sqrt(c.num(0)));
    }
    if (f == "exp") return unary_num([](double x) { return std::exp(x); });
    if (f == "pow") {
        c.arity(2);
        return num_value(c.checked(std::pow(c.num(0), c.num(1))));
    }
    if (f == "sin") return unary_num([](double x) { return std::sin(x * deg); });
    if (f == "cos") return unary_num([](double x) { return std::cos(x * deg); });
    if (f == "tan") return unary_num([](double x) { return std::tan(x * deg); });
    if (f == "asin") return unary_num([](double x) { return std::asin(x) / deg; });
    if (f == "acos") return unary_num([](double x) { return std::acos(x) / deg; });
    if (f == "atan") return unary_num([](double x) { return std::atan(x) / deg; });
    if (f == "atan2") {
        c.arity(2);
        return num_value(std::atan2(c.num(0), c.num(1)) / deg);
    }
    if (f == "round" || f == "trunc") {
        c.arity(1);
        const double scale = std::pow(10.0, c.decimals());
        const double x = c.num(0) * scale;
        return num_value(c.checked((f == "round" ? std::round(x) : std::trunc(x)) / scale));
    }
    if (f == "numtostr" || f == "dnumtostr") {
        c.arity(2);
        const int dec = c.small_int(c.num(1), 0, 15);
        std::string s = fixed(c.num(0), dec, c.option("Exp") != nullptr);
        if (s.size() > max_string_length) c.fail("result longer than 80 characters");
        return string_value(std::move(s));
    }
    if (f == "dnumtonum" || f == "numtodnum") {
        c.arity(1);
        return num_value(c.num(0));
    }
    if (f == "strlen") {
        c.arity(1);
        return num_value(static_cast<double>(c.str(0).size()));
    }
    if (f == "strpart") {
        c.arity(3);
        const std::string& s = c.str(0);
        const int n = static_cast<int>(s.size());
        const int start = c.small_int(c.num(1), 1, n + 1);
        const int len = c.small_int(c.num(2), 0, n + 1 - start);
        return string_value(
            s.substr(static_cast<std::size_t>(start - 1), static_cast<std::size_t>(len)));
    }
    if (f == "valtostr") {
        c.arity(1);
        std::string s = to_rapid_text(c.value(0));
        if (s.size() > max_string_length) c.fail("result longer than 80 characters");
        return string_value(std::move(s));
    }
    if (f == "offs") {
        c.arity(4);
        auto p = to_robtarget(c.value(0));
        if (!p) c.fail("argument 1 must be a robtarget");
        p->trans_mm += Eigen::Vector3d(c.num(1), c.num(2), c.num(3));
        return to_value(*p);
    }
    if (f == "orientzyx") {
        c.arity(3);
        const Eigen::Quaterniond q = Eigen::AngleAxisd(c.num(0) * deg, Eigen::Vector3d::UnitZ()) *
                                     Eigen::AngleAxisd(c.num(1) * deg, Eigen::Vector3d::UnitY()) *
                                     Eigen::AngleAxisd(c.num(2) * deg, Eigen::Vector3d::UnitX());
        return items_value({num_value(q.w()), num_value(q.x()), num_value(q.y()), num_value(q.z())},
                           "orient");
    }
    throw EvalError(line, "function '" + std::string(name) + "' cannot be evaluated here");
}

}  // namespace fibrecell::drivers::abb::rapid
