// SHA-256 from FIPS 180-4: constants §4.2.2, initial hash value §5.3.3, padding §5.1.1, hash
// computation §6.2.2. Rounds are written eight at a time with the working variables rotated by
// argument position instead of moved, so the loop body has no data-dependent branches.
#include "mocaplink/mavlink/sha256.hpp"

#include <algorithm>
#include <bit>

namespace mocaplink::mavlink {
namespace {

// §4.2.2: first 32 bits of the fractional parts of the cube roots of the first 64 primes.
constexpr std::array<std::uint32_t, 64> kRoundConstants = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2,
};

// §5.3.3: first 32 bits of the fractional parts of the square roots of the first 8 primes.
constexpr std::array<std::uint32_t, 8> kInitialHash = {
    0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a, 0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19,
};

// §4.1.2 functions. Ch and Maj in equivalent forms with one operation fewer.
constexpr std::uint32_t big_sigma0(std::uint32_t x) noexcept {
  return std::rotr(x, 2) ^ std::rotr(x, 13) ^ std::rotr(x, 22);
}
constexpr std::uint32_t big_sigma1(std::uint32_t x) noexcept {
  return std::rotr(x, 6) ^ std::rotr(x, 11) ^ std::rotr(x, 25);
}
constexpr std::uint32_t small_sigma0(std::uint32_t x) noexcept {
  return std::rotr(x, 7) ^ std::rotr(x, 18) ^ (x >> 3U);
}
constexpr std::uint32_t small_sigma1(std::uint32_t x) noexcept {
  return std::rotr(x, 17) ^ std::rotr(x, 19) ^ (x >> 10U);
}
constexpr std::uint32_t choose(std::uint32_t x, std::uint32_t y, std::uint32_t z) noexcept {
  return z ^ (x & (y ^ z));  // (x ∧ y) ⊕ (¬x ∧ z)
}
constexpr std::uint32_t majority(std::uint32_t x, std::uint32_t y, std::uint32_t z) noexcept {
  return (x & y) | (z & (x | y));  // (x ∧ y) ⊕ (x ∧ z) ⊕ (y ∧ z)
}

std::uint32_t load_be32(const std::uint8_t* p) noexcept {
  return (std::uint32_t{p[0]} << 24U) | (std::uint32_t{p[1]} << 16U) | (std::uint32_t{p[2]} << 8U) |
         std::uint32_t{p[3]};
}

void store_be32(std::uint32_t v, std::uint8_t* p) noexcept {
  p[0] = static_cast<std::uint8_t>(v >> 24U);
  p[1] = static_cast<std::uint8_t>(v >> 16U);
  p[2] = static_cast<std::uint8_t>(v >> 8U);
  p[3] = static_cast<std::uint8_t>(v);
}

// One round (one t) of §6.2.2 step 3 with T1 and T2 folded in: the new e is d + T1 and the new a is
// T1 + T2; every other variable only shifts one place, which the caller does by rotating the
// argument list.
inline void step(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t& d,
                 std::uint32_t e, std::uint32_t f, std::uint32_t g, std::uint32_t& h,
                 std::uint32_t k_plus_w) noexcept {
  const std::uint32_t t1 = h + big_sigma1(e) + choose(e, f, g) + k_plus_w;
  d += t1;
  h = t1 + big_sigma0(a) + majority(a, b, c);
}

// §6.2.2 for one 64-byte block.
void compress(std::array<std::uint32_t, 8>& hash, const std::uint8_t* block) noexcept {
  std::array<std::uint32_t, 64> w;  // the message schedule W, filled below
  for (std::size_t t = 0; t < 16; ++t) w[t] = load_be32(block + 4 * t);
  for (std::size_t t = 16; t < 64; ++t) {
    w[t] = small_sigma1(w[t - 2]) + w[t - 7] + small_sigma0(w[t - 15]) + w[t - 16];
  }
  std::uint32_t a = hash[0];
  std::uint32_t b = hash[1];
  std::uint32_t c = hash[2];
  std::uint32_t d = hash[3];
  std::uint32_t e = hash[4];
  std::uint32_t f = hash[5];
  std::uint32_t g = hash[6];
  std::uint32_t h = hash[7];
  for (std::size_t t = 0; t < 64; t += 8) {
    step(a, b, c, d, e, f, g, h, kRoundConstants[t + 0] + w[t + 0]);
    step(h, a, b, c, d, e, f, g, kRoundConstants[t + 1] + w[t + 1]);
    step(g, h, a, b, c, d, e, f, kRoundConstants[t + 2] + w[t + 2]);
    step(f, g, h, a, b, c, d, e, kRoundConstants[t + 3] + w[t + 3]);
    step(e, f, g, h, a, b, c, d, kRoundConstants[t + 4] + w[t + 4]);
    step(d, e, f, g, h, a, b, c, kRoundConstants[t + 5] + w[t + 5]);
    step(c, d, e, f, g, h, a, b, kRoundConstants[t + 6] + w[t + 6]);
    step(b, c, d, e, f, g, h, a, kRoundConstants[t + 7] + w[t + 7]);
  }
  hash[0] += a;
  hash[1] += b;
  hash[2] += c;
  hash[3] += d;
  hash[4] += e;
  hash[5] += f;
  hash[6] += g;
  hash[7] += h;
}

}  // namespace

Sha256::Sha256() noexcept : h_(kInitialHash) {}

void Sha256::update(std::span<const std::uint8_t> data) noexcept {
  auto used = static_cast<std::size_t>(length_bytes_ % kBlockSize);
  length_bytes_ += data.size();
  if (used != 0) {
    const std::size_t take = std::min(kBlockSize - used, data.size());
    std::copy_n(data.begin(), take, block_.begin() + static_cast<std::ptrdiff_t>(used));
    data = data.subspan(take);
    if (used + take < kBlockSize) return;
    compress(h_, block_.data());
  }
  while (data.size() >= kBlockSize) {
    compress(h_, data.data());
    data = data.subspan(kBlockSize);
  }
  std::copy(data.begin(), data.end(), block_.begin());
}

Sha256::Digest Sha256::finish() noexcept {
  // §5.1.1: a 1 bit, zeros up to 56 bytes mod 64, then the length in bits as 64-bit big-endian.
  const std::uint64_t length_bits = length_bytes_ * 8U;
  auto used = static_cast<std::size_t>(length_bytes_ % kBlockSize);
  block_[used++] = 0x80;
  if (used > kBlockSize - 8) {
    std::fill(block_.begin() + static_cast<std::ptrdiff_t>(used), block_.end(), std::uint8_t{0});
    compress(h_, block_.data());
    used = 0;
  }
  std::fill(block_.begin() + static_cast<std::ptrdiff_t>(used), block_.end() - 8, std::uint8_t{0});
  store_be32(static_cast<std::uint32_t>(length_bits >> 32U), block_.data() + kBlockSize - 8);
  store_be32(static_cast<std::uint32_t>(length_bits), block_.data() + kBlockSize - 4);
  compress(h_, block_.data());
  Digest out{};
  for (std::size_t i = 0; i < h_.size(); ++i) store_be32(h_[i], out.data() + 4 * i);
  return out;
}

}  // namespace mocaplink::mavlink
