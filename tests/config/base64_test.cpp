// Base64 of the job files carried inline in job.submit: RFC 4648's test vectors, a round trip of
// every byte value, and clear errors for text that is not base64.
#include "config/base64.hpp"

#include <gtest/gtest.h>

using namespace fibrecell::config;

TEST(Base64, Rfc4648TestVectors) {
    const std::pair<const char*, const char*> vectors[] = {
        {"", ""},         {"f", "Zg=="},         {"fo", "Zm8="},        {"foo", "Zm9v"},
        {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="}, {"foobar", "Zm9vYmFy"}};
    for (const auto& [plain, coded] : vectors) {
        EXPECT_EQ(base64_encode(plain), coded);
        EXPECT_EQ(base64_decode(coded), plain);
    }
}

TEST(Base64, EveryByteValueSurvivesARoundTrip) {
    std::string bytes;
    for (int i = 0; i < 256; ++i) bytes += static_cast<char>(i);
    for (std::size_t cut = 0; cut < 3; ++cut) {
        const std::string part = bytes.substr(cut);
        EXPECT_EQ(base64_decode(base64_encode(part)), part);
    }
}

TEST(Base64, BadTextIsRefusedWithItsOffset) {
    EXPECT_THROW(base64_decode("Zm9"), std::invalid_argument);  // length
    try {
        base64_decode("Zm9v Zg==");
        FAIL();
    } catch (const std::invalid_argument&) {
    }
    try {
        base64_decode("Zm!v");
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "base64: bad character at offset 2");
    }
    EXPECT_THROW(base64_decode("Zg=a"), std::invalid_argument);  // data after padding
    EXPECT_THROW(base64_decode("Z===" ), std::invalid_argument); // padding too early
}
