//! The x86-64 instruction-set extensions this build was compiled for (`.cargo/config.toml`
//! asks for x86-64-v3), checked against the running CPU, so that on an older CPU the program
//! stops with a message naming what is missing instead of dying on an illegal instruction.
//!
//! The standard library's `is_x86_feature_detected!` cannot do this: it answers `true` at
//! compile time for every extension the build enables. So this module reads CPUID itself.
//! The check runs before anything else and uses only integer code, which the compiler has no
//! reason to write with the extensions it checks for.

/// Where CPUID reports an extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Word {
    /// Leaf 1, register ECX.
    Leaf1Ecx,
    /// Leaf 7 (sub-leaf 0), register EBX.
    Leaf7Ebx,
    /// Leaf 0x8000_0001, register ECX.
    Ext1Ecx,
    /// Not a CPUID bit: the operating system saves the AVX registers (XCR0 bits 1 and 2),
    /// without which AVX instructions fault even on a CPU that has them.
    OsAvxState,
}

/// One extension the compiler may use: its name (as in `target_feature`), whether this build
/// was compiled with it, and the CPUID bit that says the CPU has it.
#[derive(Clone, Copy, Debug)]
pub struct Extension {
    /// The extension's `target_feature` name, e.g. `avx2`.
    pub name: &'static str,
    compiled: bool,
    word: Word,
    bit: u32,
}

/// An [`Extension`] row: its `target_feature` name, the CPUID word and bit; whether this
/// build uses it is `cfg!(target_feature = name)`.
macro_rules! ext {
    ($name:literal, $word:ident, $bit:literal) => {
        Extension {
            name: $name,
            compiled: cfg!(target_feature = $name),
            word: Word::$word,
            bit: $bit,
        }
    };
}

/// The extensions of x86-64-v2 and v3 (beyond the x86-64 baseline every x86-64 CPU has), each
/// marked with whether this build uses it.
pub const EXTENSIONS: [Extension; 17] = [
    ext!("sse3", Leaf1Ecx, 0),
    ext!("ssse3", Leaf1Ecx, 9),
    ext!("fma", Leaf1Ecx, 12),
    ext!("cmpxchg16b", Leaf1Ecx, 13),
    ext!("sse4.1", Leaf1Ecx, 19),
    ext!("sse4.2", Leaf1Ecx, 20),
    ext!("movbe", Leaf1Ecx, 22),
    ext!("popcnt", Leaf1Ecx, 23),
    ext!("xsave", Leaf1Ecx, 26),
    ext!("avx", Leaf1Ecx, 28),
    ext!("f16c", Leaf1Ecx, 29),
    ext!("bmi1", Leaf7Ebx, 3),
    ext!("avx2", Leaf7Ebx, 5),
    ext!("bmi2", Leaf7Ebx, 8),
    ext!("lzcnt", Ext1Ecx, 5),
    Extension {
        name: "operating-system support for AVX registers",
        compiled: cfg!(target_feature = "avx"),
        word: Word::OsAvxState,
        bit: 0,
    },
    // Listed so that a build for a still newer level names its first missing extension
    // rather than passing; x86-64-v3 does not use it.
    ext!("avx512f", Leaf7Ebx, 16),
];

/// The CPUID bits this build needs, per word, gathered from [`EXTENSIONS`] at compile time.
const NEED: CpuWords = {
    let mut need = CpuWords {
        leaf1_ecx: 0,
        leaf7_ebx: 0,
        ext1_ecx: 0,
        os_avx_state: false,
    };
    let mut i = 0;
    while i < EXTENSIONS.len() {
        let e = EXTENSIONS[i];
        if e.compiled {
            match e.word {
                Word::Leaf1Ecx => need.leaf1_ecx |= 1 << e.bit,
                Word::Leaf7Ebx => need.leaf7_ebx |= 1 << e.bit,
                Word::Ext1Ecx => need.ext1_ecx |= 1 << e.bit,
                Word::OsAvxState => need.os_avx_state = true,
            }
        }
        i += 1;
    }
    need
};

/// The CPUID words the check reads, taken once.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CpuWords {
    leaf1_ecx: u32,
    leaf7_ebx: u32,
    ext1_ecx: u32,
    os_avx_state: bool,
}

impl CpuWords {
    fn has(&self, word: Word, bit: u32) -> bool {
        match word {
            Word::Leaf1Ecx => self.leaf1_ecx >> bit & 1 == 1,
            Word::Leaf7Ebx => self.leaf7_ebx >> bit & 1 == 1,
            Word::Ext1Ecx => self.ext1_ecx >> bit & 1 == 1,
            Word::OsAvxState => self.os_avx_state,
        }
    }

    /// Has this CPU every bit of `need`? Constant masks only: see [`runs_here`].
    #[inline(always)]
    fn covers(&self, need: &CpuWords) -> bool {
        (self.leaf1_ecx & need.leaf1_ecx == need.leaf1_ecx)
            & (self.leaf7_ebx & need.leaf7_ebx == need.leaf7_ebx)
            & (self.ext1_ecx & need.ext1_ecx == need.ext1_ecx)
            & (self.os_avx_state | !need.os_avx_state)
    }
}

/// Reads the running CPU's words (all zero but on x86-64, where nothing is compiled in
/// beyond the baseline and nothing is checked).
#[inline(always)]
pub fn read() -> CpuWords {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::__cpuid_count;
        // CPUID exists on every x86-64 CPU. (`unsafe` for Rust versions that declare it so.)
        #[allow(unused_unsafe)]
        let cpuid = |leaf: u32| unsafe { __cpuid_count(leaf, 0) };
        let max_leaf = cpuid(0).eax;
        let max_ext = cpuid(0x8000_0000).eax;
        let leaf1_ecx = cpuid(1).ecx;
        let leaf7_ebx = if max_leaf >= 7 { cpuid(7).ebx } else { 0 };
        let ext1_ecx = if max_ext >= 0x8000_0001 {
            cpuid(0x8000_0001).ecx
        } else {
            0
        };
        // XGETBV may only run when the OS has enabled it (OSXSAVE, leaf 1 ECX bit 27).
        let os_avx_state = leaf1_ecx & 1 << 27 != 0 && xcr0() & 0b110 == 0b110;
        CpuWords {
            leaf1_ecx,
            leaf7_ebx,
            ext1_ecx,
            os_avx_state,
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    CpuWords::default()
}

/// The low word of XCR0, the register in which the OS says which register states it saves.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn xcr0() -> u32 {
    let low: u32;
    // SAFETY: only called when CPUID reports OSXSAVE, so XGETBV is enabled; it reads a
    // register and touches no memory.
    unsafe {
        std::arch::asm!(
            "xgetbv",
            in("ecx") 0u32,
            out("eax") low,
            out("edx") _,
            options(nomem, nostack, preserves_flags)
        );
    }
    low
}

/// Whether the running CPU has every extension this build uses.
///
/// It runs first thing in `main`, so it must not itself use them. Every extension's code is
/// something the compiler may pick for ordinary Rust (BMI2's `shlx` for a variable shift, a
/// VEX-encoded move for a copy), so this function is CPUID and XGETBV (inline assembly, which
/// the compiler does not rewrite) and `and`/compare against constant masks, and nothing else:
/// no loop, no variable shift, no memory copy. `tests/cli/old_cpus.rs` runs the binary on
/// emulated CPUs without AVX (with `qemu-x86_64`, which `.ci/run` installs).
#[inline(never)]
pub fn runs_here() -> bool {
    read().covers(&NEED)
}

/// The names of the extensions this build uses and `cpu` lacks (for tests and diagnostics;
/// unlike [`runs_here`], it is not safe to run on such a CPU).
pub fn missing(cpu: &CpuWords) -> Vec<&'static str> {
    EXTENSIONS
        .iter()
        .filter(|e| e.compiled && !cpu.has(e.word, e.bit))
        .map(|e| e.name)
        .collect()
}

/// What `main` prints, with nothing computed, when [`runs_here`] says no.
pub const MESSAGE: &str = "error: this berry-evolve was built for x86-64 instruction-set \
extensions that this CPU lacks (x86-64-v3, asked for by .cargo/config.toml: AVX, AVX2, FMA, \
BMI1, BMI2, LZCNT, MOVBE, F16C; or the CPU named in RUSTFLAGS when it was built)
  hint: build it for this CPU with `RUSTFLAGS=\"-C target-cpu=native\" cargo build --release`; \
results are the same bytes either way
";

#[cfg(test)]
mod tests {
    use super::*;

    fn all_bits() -> CpuWords {
        CpuWords {
            leaf1_ecx: u32::MAX,
            leaf7_ebx: u32::MAX,
            ext1_ecx: u32::MAX,
            os_avx_state: true,
        }
    }

    /// The names of `list`'s extensions, all taken as compiled in, that `cpu` lacks.
    fn lacking(list: &[Extension], cpu: &CpuWords) -> Vec<&'static str> {
        list.iter()
            .filter(|e| !cpu.has(e.word, e.bit))
            .map(|e| e.name)
            .collect()
    }

    #[test]
    fn a_cpu_with_every_bit_lacks_nothing() {
        assert!(lacking(&EXTENSIONS, &all_bits()).is_empty());
        assert!(all_bits().covers(&NEED));
    }

    #[test]
    fn each_cleared_bit_names_its_extension() {
        // The CPUID bits of the Intel and AMD manuals.
        let expected = [
            ("avx2", Word::Leaf7Ebx, 5),
            ("fma", Word::Leaf1Ecx, 12),
            ("bmi1", Word::Leaf7Ebx, 3),
            ("bmi2", Word::Leaf7Ebx, 8),
            ("avx", Word::Leaf1Ecx, 28),
            ("lzcnt", Word::Ext1Ecx, 5),
            ("movbe", Word::Leaf1Ecx, 22),
            ("sse4.2", Word::Leaf1Ecx, 20),
        ];
        for (name, word, bit) in expected {
            let mut cpu = all_bits();
            match word {
                Word::Leaf1Ecx => cpu.leaf1_ecx &= !(1 << bit),
                Word::Leaf7Ebx => cpu.leaf7_ebx &= !(1 << bit),
                Word::Ext1Ecx => cpu.ext1_ecx &= !(1 << bit),
                Word::OsAvxState => unreachable!(),
            }
            assert_eq!(lacking(&EXTENSIONS, &cpu), [name], "bit {bit} of {word:?}");
        }
    }

    #[test]
    fn avx_registers_not_saved_by_the_os_count_as_missing() {
        let cpu = CpuWords {
            os_avx_state: false,
            ..all_bits()
        };
        let names = lacking(&EXTENSIONS, &cpu);
        assert_eq!(names.len(), 1);
        assert!(names[0].contains("AVX registers"));
    }

    #[test]
    fn the_constant_masks_say_what_the_table_says() {
        // runs_here tests the masks; missing walks the table. For every single cleared bit
        // of every word, both must agree on whether this build can run.
        for word in [
            Word::Leaf1Ecx,
            Word::Leaf7Ebx,
            Word::Ext1Ecx,
            Word::OsAvxState,
        ] {
            for bit in 0..32 {
                let mut cpu = all_bits();
                match word {
                    Word::Leaf1Ecx => cpu.leaf1_ecx &= !(1 << bit),
                    Word::Leaf7Ebx => cpu.leaf7_ebx &= !(1 << bit),
                    Word::Ext1Ecx => cpu.ext1_ecx &= !(1 << bit),
                    Word::OsAvxState => cpu.os_avx_state = false,
                }
                assert_eq!(
                    cpu.covers(&NEED),
                    missing(&cpu).is_empty(),
                    "{word:?} bit {bit}"
                );
            }
        }
        // A CPU with no extension at all runs exactly the builds that use none.
        let baseline = CpuWords::default();
        let uses_any = EXTENSIONS.iter().any(|e| e.compiled);
        assert_eq!(baseline.covers(&NEED), !uses_any);
        assert_eq!(missing(&baseline).is_empty(), !uses_any);
    }

    #[test]
    fn the_machine_running_the_tests_has_what_the_build_uses() {
        // This test binary is itself built with the extensions, so it could only get here on
        // a CPU that has them: any name reported is a wrong CPUID bit or a wrong reading.
        assert_eq!(missing(&read()), Vec::<&str>::new());
        assert!(runs_here());
    }
}
