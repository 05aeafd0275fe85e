// The dashboard's login bookkeeping with the time passed in: session expiry, the per-address
// and overall limits on wrong tokens, and reading the session cookie out of a Cookie header.
#include "daemon/http/login_sessions.hpp"

#include <gtest/gtest.h>

#include <set>

using namespace fibrecell::http;
using namespace std::chrono_literals;

TEST(SessionTable, ASessionLastsItsLifetimeAndNoLonger) {
    SessionTable sessions(3600s, 8);
    const Clock::time_point t0{};
    const std::string id = sessions.open(t0);
    EXPECT_EQ(id.size(), 64u);
    EXPECT_TRUE(sessions.valid(id, t0 + 3599s));
    EXPECT_FALSE(sessions.valid(id, t0 + 3600s));
    EXPECT_FALSE(sessions.valid(id, t0));  // gone once expired
    EXPECT_FALSE(sessions.valid("", t0));
    EXPECT_FALSE(sessions.valid(std::string(64, '0'), t0));
}

TEST(SessionTable, IdsAreFreshAndTheOldestGoesWhenFull) {
    SessionTable sessions(3600s, 3);
    const Clock::time_point t0{};
    std::vector<std::string> ids;
    for (int i = 0; i < 4; ++i) ids.push_back(sessions.open(t0 + std::chrono::seconds(i)));
    EXPECT_EQ(std::set<std::string>(ids.begin(), ids.end()).size(), 4u);
    EXPECT_EQ(sessions.size(), 3u);
    EXPECT_FALSE(sessions.valid(ids[0], t0 + 10s));
    EXPECT_TRUE(sessions.valid(ids[3], t0 + 10s));
    sessions.close(ids[3]);
    EXPECT_FALSE(sessions.valid(ids[3], t0 + 10s));
    sessions.close_all();
    EXPECT_FALSE(sessions.valid(ids[2], t0 + 10s));
}

TEST(LoginGuard, TooManyWrongTokensWaitUntilTheOldestIsAMinuteOld) {
    LoginGuard guard(3);
    const Clock::time_point t0{};
    guard.failed("10.0.0.1", t0);
    guard.failed("10.0.0.1", t0 + 10s);
    EXPECT_FALSE(guard.wait_for("10.0.0.1", t0 + 11s));
    guard.failed("10.0.0.1", t0 + 20s);
    ASSERT_TRUE(guard.wait_for("10.0.0.1", t0 + 21s));
    EXPECT_EQ(*guard.wait_for("10.0.0.1", t0 + 21s), 39s);
    EXPECT_FALSE(guard.wait_for("10.0.0.2", t0 + 21s)) << "another address is not held back";
    EXPECT_FALSE(guard.wait_for("10.0.0.1", t0 + 60s)) << "the first failure is a minute old";
    guard.succeeded("10.0.0.1");
    guard.failed("10.0.0.1", t0 + 61s);
    EXPECT_FALSE(guard.wait_for("10.0.0.1", t0 + 61s));
}

// 200 addresses, one wrong token each: together they meet a limit of their own (four times an
// address's), and then every address waits, the one with no failure of its own too.
TEST(LoginGuard, ManyAddressesDoNotAddUpToMoreGuesses) {
    LoginGuard guard(3);
    const Clock::time_point t0{};
    int tried = 0;
    for (int i = 0; i < 200; ++i) {
        const std::string address = "127.0.0." + std::to_string(i + 1);
        if (guard.wait_for(address, t0 + 1s)) continue;
        guard.failed(address, t0 + 1s);
        ++tried;
    }
    EXPECT_EQ(tried, 3 * LoginGuard::kAddressesPerLimit);
    ASSERT_TRUE(guard.wait_for("10.9.9.9", t0 + 2s));
    EXPECT_EQ(*guard.wait_for("10.9.9.9", t0 + 2s), 59s);
    EXPECT_FALSE(guard.wait_for("10.9.9.9", t0 + 61s)) << "a minute on, logins are open again";
}

TEST(CookieValue, FindsTheNamedCookieOnly) {
    EXPECT_EQ(cookie_value("a=1; fibrecell_session=ab12; b=2", "fibrecell_session"), "ab12");
    EXPECT_EQ(cookie_value("fibrecell_session=x", "fibrecell_session"), "x");
    EXPECT_EQ(cookie_value("xfibrecell_session=y; a=b", "fibrecell_session"), "");
    EXPECT_EQ(cookie_value("", "fibrecell_session"), "");
    EXPECT_EQ(cookie_value("fibrecell_session", "fibrecell_session"), "");
}
