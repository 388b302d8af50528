// Verilator C++ harness template for bulk runs (gbump fills the double-braced fields).
// Streams fixed-size binary records through the Verilated pipeline with valid/ready, checks
// every out_c in order and, for every vector, the timing the interface file states (out_valid
// sampled high exactly LATENCY rising edges after the accepting edge; accepts exactly II edges
// apart while a fragment is on offer), stops after --max-errors mismatches (default 20)
// printing every field, and ends with "N passed, N failed". Without --table the pipeline runs
// on its power-up table (INIT_FILE); --bubbles N idles in_valid 1-3 cycles before every Nth
// record. A record that starts a triangle (per-triangle tops: its tri_start bit) is preceded
// by a setup beat on tri_valid/tri_ready with in_valid low. --dump FILE writes each out_c as 8 little-endian bytes
// (for rendering an image through the RTL); --no-check skips comparison (raw speed runs).
// --raw CYCLES clocks the model that many cycles on the first record with no file I/O and
// prints its evaluation rate (the upper bound of any regression).
// --vectors - --count N reads N records from standard input (a pipe from `gbump regress
// --stream`): records are read in blocks into a ring, so memory stays constant for any N.
// Usage: harness --vectors FILE.bin|- [--count N] [--table FILE.hex] [--MEMORY FILE.hex] [--bubbles N] [--stall N] [--dump FILE] [--max-errors N] [--raw CYCLES]
// (--MEMORY: another memory of the top, loaded through its port after the table: EMBM's
// --env-diffuse and --env-specular, a scene set's object maps)
#include "V{{TOP}}.h"
#include "verilated.h"
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <algorithm>
#include <cerrno>
#include <fcntl.h>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>
#include <sstream>
#include <string>
#include <vector>

static const size_t RECORD_BYTES = {{RECORD_BYTES}};
static const int POWER_TABLE_WORDS = {{POWER_TABLE_WORDS}};
static const long long LATENCY = {{LATENCY}};
static const long long II = {{II}};
static const size_t FLIGHT = 64;
// Per-triangle tops: a setup loads bank (setups so far + 1) % TRI_BANKS, and may do so from
// BANK_HOLD edges after the accept of that bank's last fragment on, not before; and it spans
// SETUP_EDGES edges from the first it is offered at. From both on, tri_ready is high.
static const unsigned TRI_BANKS = {{TRI_BANKS}};
static const long long BANK_HOLD = {{BANK_HOLD}};
static const long long SETUP_EDGES = {{SETUP_EDGES}};
// Tops with out_ready: the output buffer's depth (0: no out_ready). A result is offered
// (out_valid) from LATENCY edges after its accept on, never before, and stays offered until
// taken; --stall N holds out_ready low for the first 1-3 edges (at most N) of every N edges.
static const size_t OUT_DEPTH = {{OUT_DEPTH}};

// Bits [lsb, lsb+width) of a little-endian record (width <= 64): one unaligned 8-byte load
// and a shift. The record buffer is padded so the load never leaves it.
static inline uint64_t get_bits(const uint8_t* rec, unsigned lsb, unsigned width) {
    unsigned byte = lsb >> 3, sh = lsb & 7;
    uint64_t v;
    memcpy(&v, rec + byte, 8);
    v >>= sh;
    if (sh + width > 64) v |= (uint64_t)rec[byte + 8] << (64 - sh);
    return width >= 64 ? v : (v & ((1ull << width) - 1));
}

// The records of a file or a pipe, read in blocks into a ring as the loop asks for them. Why
// not the whole file in memory: a stream has no end to load, and a file of millions of records
// cost page faults and zeroing that the ring (a quarter of a megabyte, in cache) does not.
struct Records {
    int fd = -1;
    const char* name = "";
    size_t n = 0;       // records the run holds
    size_t cap = 0;     // ring slots (a power of two)
    size_t bytes = 0;   // bytes read so far
    size_t loaded = 0;  // whole records read so far
    std::vector<uint8_t> ring;

    // Open `path` ("-": standard input, `count` records; a file: its size says how many).
    bool open(const char* path, long long count) {
        name = path;
        if (!strcmp(path, "-")) {
            fd = 0;
            name = "standard input";
            if (count <= 0) { fprintf(stderr, "FATAL: --vectors - needs --count N (N >= 1)\n"); return false; }
            n = (size_t)count;
        } else {
            fd = ::open(path, O_RDONLY);
            struct stat st;
            if (fd < 0 || fstat(fd, &st) != 0) { fprintf(stderr, "FATAL: cannot open %s\n", path); return false; }
            if (st.st_size <= 0 || st.st_size % (off_t)RECORD_BYTES != 0) { fprintf(stderr, "FATAL: %s: %lld bytes is not a whole number of %zu-byte records\n", path, (long long)st.st_size, RECORD_BYTES); return false; }
            n = (size_t)st.st_size / RECORD_BYTES;
            if (count > 0 && (size_t)count != n) { fprintf(stderr, "FATAL: %s holds %zu records, --count says %lld\n", path, n, count); return false; }
        }
        cap = 256;
        while (cap * 2 * RECORD_BYTES <= (256u << 10)) cap *= 2;
        // Padded so get_bits' 8-byte load never leaves the ring.
        ring.assign(cap * RECORD_BYTES + 16, 0);
        return true;
    }
    // Record i, read earlier (at most cap records behind the newest).
    const uint8_t* at(size_t i) const { return ring.data() + (i & (cap - 1)) * RECORD_BYTES; }
    // Record i (< n), reading ahead as far as the ring holds without overwriting record `oldest`,
    // the oldest one still needed.
    const uint8_t* next(size_t i, size_t oldest) {
        while (loaded <= i) {
            const size_t ring_bytes = cap * RECORD_BYTES, pos = bytes % ring_bytes;
            const size_t end = std::min(n, oldest + cap) * RECORD_BYTES;
            const size_t room = std::min(ring_bytes - pos, end - bytes);
            const ssize_t got = read(fd, ring.data() + pos, room);
            if (got < 0 && errno == EINTR) continue;
            if (got <= 0) {
                fprintf(stderr, "FATAL: %s ended after %zu of %zu records\n", name, loaded, n);
                exit(2);
            }
            bytes += (size_t)got;
            loaded = bytes / RECORD_BYTES;
        }
        return at(i);
    }
};

// CPU seconds of this process: a speed figure that other programs on the machine do not skew.
static double cpu_seconds() {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

// Words up to 64 bits (a map's {B, G, R} is 3 x colour_bits wide).
static bool read_words(const char* path, std::vector<uint64_t>& out, int words) {
    std::ifstream f(path);
    if (!f) return false;
    std::string line;
    while (std::getline(f, line)) {
        size_t c = line.find("//");
        if (c != std::string::npos) line = line.substr(0, c);
        std::stringstream ss(line);
        std::string tok;
        if (ss >> tok) out.push_back((uint64_t)strtoull(tok.c_str(), nullptr, 16));
    }
    return (int)out.size() == words;
}

int main(int argc, char** argv) {
    const char* vec_path = nullptr;
    const char* table_path = nullptr;
    const char* dump_path = nullptr;
    long max_errors = 20;
    bool check = true;
    long long raw_cycles = 0;
    long long count = 0;
    long bubbles = 0;
    long stall = 0;
{{MEM_VARS}}
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--vectors") && i + 1 < argc) vec_path = argv[++i];
        else if (!strcmp(argv[i], "--table") && i + 1 < argc) table_path = argv[++i];
        else if (!strcmp(argv[i], "--dump") && i + 1 < argc) dump_path = argv[++i];
        else if (!strcmp(argv[i], "--max-errors") && i + 1 < argc) max_errors = atol(argv[++i]);
        else if (!strcmp(argv[i], "--no-check")) check = false;
        else if (!strcmp(argv[i], "--raw") && i + 1 < argc) raw_cycles = atoll(argv[++i]);
        else if (!strcmp(argv[i], "--bubbles") && i + 1 < argc) bubbles = atol(argv[++i]);
        else if (!strcmp(argv[i], "--stall") && i + 1 < argc) stall = atol(argv[++i]);
        else if (!strcmp(argv[i], "--count") && i + 1 < argc) count = atoll(argv[++i]);
{{MEM_ARGS}}
        else { fprintf(stderr, "FATAL: unknown argument %s\n", argv[i]); return 2; }
    }
    if (!vec_path) { fprintf(stderr, "FATAL: usage: %s --vectors FILE.bin [--table FILE.hex]\n", argv[0]); return 2; }
    std::vector<uint64_t> table;
    if (table_path && !read_words(table_path, table, POWER_TABLE_WORDS)) { fprintf(stderr, "FATAL: %s: expected %d table entries\n", table_path, POWER_TABLE_WORDS); return 2; }
{{MEM_READ}}
    Records recs;
    if (!recs.open(vec_path, count)) return 2;
    const size_t n = recs.n;
    std::vector<uint64_t> dump;
    if (dump_path) dump.reserve(n);

    VerilatedContext ctx;
    ctx.commandArgs(argc, argv);
    V{{TOP}} top(&ctx);
    auto tick = [&]() { top.clk = 0; top.eval(); top.clk = 1; top.eval(); };
    top.rst = 1; top.in_valid = 0; top.power_table_we = 0;
    {{TRI_VALID_0}}
    {{OUT_READY_1}}
    for (int i = 0; i < {{RESET_CYCLES}}; ++i) tick();
    top.rst = 0;
    if (table_path)
        for (int i = 0; i < POWER_TABLE_WORDS; ++i) { top.power_table_we = 1; top.power_table_waddr = i; top.power_table_wdata = table[i]; tick(); }
    top.power_table_we = 0;
{{MEM_LOAD}}

    if (raw_cycles > 0) {
        const uint8_t* rin = recs.next(0, 0);
{{ASSIGN}}
        // A per-triangle top loads the first record's triangle before the fragments.
        {{RAW_SETUP}}
        top.in_valid = 1;
        auto r0 = std::chrono::steady_clock::now();
        const double c0 = cpu_seconds();
        for (long long c = 0; c < raw_cycles; ++c) tick();
        double rs = std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
        printf("raw: %lld cycles in %.3f s, %.0f cycles/s, %.0f fragments/s, %.3f s of CPU\n", raw_cycles, rs, raw_cycles / rs, raw_cycles / rs / (double)II, cpu_seconds() - c0);
        printf("1 passed, 0 failed\n");
        top.final();
        return 0;
    }
    size_t next_in = 0, next_out = 0;
    long passed = 0, failed = 0, timing_errors = 0;
    // The digest of the records checked, printed beside the summary so a pass shows which
    // records were compared: each record's little-endian 64-bit words XORed, taken as
    // d = rotl(d, 1) ^ f.
    uint64_t digest = 0;
    auto fold = [&](const uint8_t* r) {
        uint64_t f = 0;
        for (size_t k = 0; k < RECORD_BYTES; k += 8) {
            uint64_t w = 0;
            memcpy(&w, r + k, RECORD_BYTES - k < 8 ? RECORD_BYTES - k : 8);
            f ^= w;
        }
        digest = (digest << 1 | digest >> 63) ^ f;
    };
    // Edges since the top last took or gave anything; at WAIT_EDGES the run ends failed (a top
    // that stops answering ends the run rather than hanging it).
    uint64_t cycles = 0, idle = 0;
    const uint64_t WAIT_EDGES = LATENCY * 4 + 100;
    bool setup = false;
    // Timing: the edge of every accept still in flight, and of the last one.
    long long acc_cyc[FLIGHT];
    long long last_acc = -1;
    long gap = 0;
    size_t gapped_for = (size_t)-1;
    // The record whose triangle setup was accepted last; setups and their waits.
    size_t setup_for = (size_t)-1;
    // The record whose setup is offered, and the first edge it was offered at.
    size_t offer_for = (size_t)-1;
    long long offer_at = 0;
    unsigned long long setups = 0, setup_waits = 0;
    std::vector<long long> frag_edge(TRI_BANKS, -1000000);
    auto timing = [&](const char* what, long long got, long long want) {
        ++failed;
        if (++timing_errors <= max_errors)
            printf("MISMATCH unit gbump_pipeline timing: %s: %lld rising edges, the interface states %lld (vector %zu, edge %llu)\n", what, got, want, next_out, (unsigned long long)cycles);
    };
    auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_seconds();
    // The record whose fields are on the inputs: a record offered for several edges (waiting
    // for in_ready or tri_ready) is unpacked once.
    size_t assigned = (size_t)-1;
    while (next_out < n && idle < WAIT_EDGES && failed < max_errors) {
        const uint8_t* rin = next_in < n ? recs.next(next_in, next_out) : nullptr;
        if (bubbles > 0 && next_in < n && next_in % bubbles == (size_t)bubbles - 1 && gapped_for != next_in) {
            gap = 1 + (long)((next_in / bubbles) % 3);
            gapped_for = next_in;
        }
        setup = false;
        if (next_in < n && gap == 0) {
          if (assigned != next_in) {
            assigned = next_in;
{{ASSIGN}}
          }
            setup = {{TRI_START}} && setup_for != next_in;
            top.in_valid = !setup;
        } else {
            top.in_valid = 0;
        }
        if (setup) { {{TRI_VALID_1}} } else { {{TRI_VALID_0}} }
        bool out_ready = !(stall > 0 && (long)(cycles % stall) <= (long)((cycles / stall) % 3));
        {{OUT_READY_SET}}
        top.clk = 0;
        top.eval();
        // Sampled before the rising edge, as the design's registers see them.
        bool accept = top.in_valid && top.in_ready;
        if (setup) {
            if (offer_for != next_in) { offer_for = next_in; offer_at = (long long)cycles; }
            const long long since = (long long)cycles - frag_edge[(setups + 1) % TRI_BANKS];
            const long long offered = (long long)cycles - offer_at;
            const bool taken = {{TRI_ACCEPT}};
            if (taken && since < BANK_HOLD) timing("setup accepted while its bank is still read", since, BANK_HOLD);
            else if (taken && offered < SETUP_EDGES - 1) timing("setup accepted before it spans its edges", offered + 1, SETUP_EDGES);
            else if (!taken && since >= BANK_HOLD && offered >= SETUP_EDGES - 1) timing("tri_ready low beyond the bank hold", since, BANK_HOLD);
            if (taken) { setup_for = next_in; ++setups; idle = 0; }
            else ++setup_waits;
        }
        const long long cyc = (long long)cycles;
        if (accept) {
            if (last_acc >= 0 && cyc - last_acc < II) timing("accepts closer than the initiation interval", cyc - last_acc, II);
            if (next_in - next_out >= FLIGHT) { printf("FATAL: more than %zu fragments in flight\n", FLIGHT); break; }
            if (OUT_DEPTH > 0 && next_in - next_out >= OUT_DEPTH) timing("accepted while the output buffer's untaken results fill it", (long long)(next_in - next_out), (long long)OUT_DEPTH);
            acc_cyc[next_in % FLIGHT] = cyc;
            last_acc = cyc;
            idle = 0;
            frag_edge[setups % TRI_BANKS] = cyc;
        } else if (top.in_valid && (last_acc < 0 || cyc - last_acc >= II) && (OUT_DEPTH == 0 || next_in - next_out < OUT_DEPTH)) {
            timing("in_ready low beyond the initiation interval", last_acc < 0 ? cyc : cyc - last_acc, II);
        }
        // The integration notes promise out_c = 0 whenever out_valid is low.
        if (!top.out_valid && top.out_c != 0) {
            ++failed;
            if (++timing_errors <= max_errors)
                printf("MISMATCH unit gbump_pipeline: out_c is not 0 while out_valid is low: out_c=%llx (vector %zu, edge %llu)\n", (unsigned long long)top.out_c, next_out, (unsigned long long)cycles);
        }
        if (!top.out_valid && next_out < next_in && cyc - acc_cyc[next_out % FLIGHT] >= LATENCY)
            timing("latency: the result is not offered", cyc - acc_cyc[next_out % FLIGHT], LATENCY);
        if (top.out_valid && next_out >= next_in + (accept ? 1 : 0)) { timing("out_valid with no fragment in flight", 0, LATENCY); break; }
        if (top.out_valid && cyc - acc_cyc[next_out % FLIGHT] < LATENCY) timing("latency: the result is offered early", cyc - acc_cyc[next_out % FLIGHT], LATENCY);
        else if (top.out_valid && out_ready) {
            idle = 0;
            const uint8_t* rec = recs.at(next_out);
            fold(rec);
            uint64_t want = get_bits(rec, {{OUT_LSB}}, {{OUT_W}});
            uint64_t got = (uint64_t)top.out_c;
            if (dump_path) dump.push_back(got);
            if (!check || want == got) ++passed;
            else {
                ++failed;
                if (failed <= max_errors) {
                    printf("MISMATCH unit gbump_pipeline vector %zu:\n", next_out);
{{PRINT}}
                    printf("  out_c expected %llx got %llx\n", (unsigned long long)want, (unsigned long long)got);
                }
            }
            ++next_out;
        } else {
            ++idle;
        }
        top.clk = 1;
        top.eval();
        ++cycles;
        if (accept) ++next_in;
        if (gap > 0) --gap;
    }
    if (failed >= max_errors) printf("stopping after %ld mismatches\n", failed);
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (idle >= WAIT_EDGES && next_in < n)
        printf("FATAL: %s stayed low for %llu edges before record %zu: the top stopped taking %s\n", setup ? "tri_ready" : "in_ready",
               (unsigned long long)idle, next_in, setup ? "setups" : "fragments");
    if (next_out < n && failed < max_errors) {
        printf("MISMATCH: %zu fragments went in but %zu came out\n", next_in, next_out);
        failed += (long)(n - next_out);
    }
    if (dump_path) {
        FILE* df = fopen(dump_path, "wb");
        if (!df || fwrite(dump.data(), 8, dump.size(), df) != dump.size()) { fprintf(stderr, "FATAL: cannot write %s\n", dump_path); return 2; }
        fclose(df);
    }
    if (setups) printf("%llu triangle setups, %llu edges waited for tri_ready, %llu edges in all\n", setups, setup_waits, (unsigned long long)cycles);
    fprintf(stderr, "%zu vectors, %llu cycles, %.3f s, %.0f vectors/s, %.3f s of CPU\n", n, (unsigned long long)cycles, secs, n / (secs > 0 ? secs : 1e-9), cpu_seconds() - c0);
    printf("digest %016llx\n", (unsigned long long)digest);
    printf("%ld passed, %ld failed\n", passed, failed);
    top.final();
    return failed ? 1 : (passed ? 0 : 1);
}
