//! Property tests: FORMAT/SCAN round trips, CRC against independent
//! oracles, EXTRACT after REPLACE.

mod common;
use common::*;
use linc_stdlib::Value;
use proptest::prelude::*;

fn format(fmt: &str, v: Value) -> Value {
    f("FORMAT", &[s(fmt), v])
}

fn scan(fmt: &str, text: Value) -> Value {
    f("SCAN", &[s(fmt), text])
}

// ---------------------------------------------------------------- FORMAT/SCAN

/// Integer conversions and the range each one round-trips over. `I` covers
/// every INT; `U`, `x`, `X`, `B` and `O` write the 32-bit pattern as
/// unsigned and SCAN gives the same pattern back, so they too cover every
/// INT. A width only has to be wide enough for the longest text.
const WHOLE_RANGE: &[&str] =
    &["I", "11I", "011I", "12I!", "U", "10U", "010U", "x", "X", "08x", "8X", "B", "032B", "O", "011O"];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn integer_conversions_round_trip_over_every_int(v in any::<i32>()) {
        for fmt in WHOLE_RANGE {
            let text = format(fmt, i(v));
            prop_assert_ne!(&text, &null(), "{}", fmt);
            prop_assert_eq!(scan(fmt, text.clone()), i(v), "{} {:?}", fmt, text);
            prop_assert_eq!(f("IS_VALID", &[s(fmt), text]), Value::Bool(true));
        }
    }

    #[test]
    fn narrow_widths_round_trip_over_their_range(v in 0..=0xFFFF_i32) {
        // 5 decimal digits, 4 hex digits, 16 binary digits, 6 octal digits
        // hold every 16-bit unsigned value.
        for fmt in ["5U", "05U", "04X", "4x", "016B", "6O", "5I"] {
            let text = format(fmt, i(v));
            prop_assert_eq!(scan(fmt, text), i(v), "{}", fmt);
        }
        let text = format("6I", i(-v / 2));
        prop_assert_eq!(scan("I", text), i(-v / 2));
    }

    #[test]
    fn too_narrow_widths_overflow(v in 100_000..=i32::MAX) {
        prop_assert_eq!(format("5U", i(v)), s("*****"));
        prop_assert_eq!(format("5I?", i(v)), s("?????"));
    }

    #[test]
    fn chars_round_trip(v in 0..=255_i32) {
        prop_assert_eq!(scan("C", format("C", i(v))), i(v));
    }

    #[test]
    fn times_round_trip(h in 0..24_i32, m in 0..60_i32, sec in 0..60_i32, dot in any::<bool>()) {
        let (ft, ftp) = if dot { ("T.", "TP.") } else { ("T", "TP") };
        let iso = h * 10_000 + m * 100 + sec;
        prop_assert_eq!(scan(ft, format(ft, i(iso))), i(iso));
        let posix = h * 3600 + m * 60 + sec;
        prop_assert_eq!(scan(ftp, format(ftp, i(posix))), i(posix));
        prop_assert_eq!(format(ftp, i(posix + 86_400 * 1000)), format(ftp, i(posix)));
    }

    #[test]
    fn dates_round_trip(days in -25_567..=24_855_i64) {
        // From 1900-01-01 to 2038-01-19: D over all of it, DP over the days
        // whose two-digit year maps back (1969 to 2038-01-19).
        let secs = days * 86_400;
        let (y, mo, d) = civil(days);
        let iso = (y * 10_000 + mo * 100 + d) as i32;
        prop_assert_eq!(scan("D", format("D", i(iso))), i(iso));
        if y >= 1969 {
            let secs = secs as i32;
            prop_assert_eq!(scan("DP", format("DP", i(secs))), i(secs));
            // Any time within the day formats as the same date (the last day
            // before 2038-01-19 has no DINT second at its end).
            if let Some(end) = secs.checked_add(86_399) {
                prop_assert_eq!(format("DP", i(end)), format("DP", i(secs)));
            }
        }
    }

    #[test]
    fn reals_round_trip_through_e_and_g(x in any::<f32>().prop_filter("finite", |x| x.is_finite())) {
        // Nine significant digits identify every f32.
        let text = format(".8E", r(x));
        prop_assert_eq!(scan("G", text), r(x));
        let text = format(".60F", r(x));
        prop_assert_eq!(scan("F", text), r(x));
    }

    #[test]
    fn format_fills_the_width_exactly(w in 1..40_usize, v in any::<i32>(), conv in 0..8_usize) {
        let letter = ["I", "U", "x", "X", "B", "O", "F", ".3E"][conv];
        let fmt = format!("{w}{letter}");
        let len = format(&fmt, i(v)).as_bytes().len();
        // F without a '.' leaves out the point column when the value fits.
        prop_assert!(len == w || (letter == "F" && len + 1 == w), "{} {}", fmt, len);
    }
}

/// An independent civil-from-days (a day-by-day walk from 1900).
fn civil(days_since_1970: i64) -> (i64, i64, i64) {
    let mut days = days_since_1970 + 25_567; // days from 1900-01-01
    let mut y = 1900;
    loop {
        let leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
        let len = if leap { 366 } else { 365 };
        if days < len {
            let months = [31, if leap { 29 } else { 28 }, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
            for (m, ml) in (1..).zip(months) {
                if days < ml {
                    return (y, m, days + 1);
                }
                days -= ml;
            }
        }
        days -= len;
        y += 1;
    }
}

// ---------------------------------------------------------------------- CRC

/// A published CRC-16 with no final XOR and refin = refout.
struct Params {
    name: &'static str,
    poly: u16,
    init: u16,
    reflected: bool,
    check: u16,
    oracle: &'static crc::Algorithm<u16>,
}

const SETS: &[Params] = &[
    Params {
        name: "CRC-16/MODBUS",
        poly: 0x8005,
        init: 0xFFFF,
        reflected: true,
        check: 0x4B37,
        oracle: &crc::CRC_16_MODBUS,
    },
    Params { name: "CRC-16/ARC", poly: 0x8005, init: 0x0000, reflected: true, check: 0xBB3D, oracle: &crc::CRC_16_ARC },
    Params {
        name: "CRC-16/XMODEM",
        poly: 0x1021,
        init: 0x0000,
        reflected: false,
        check: 0x31C3,
        oracle: &crc::CRC_16_XMODEM,
    },
    Params {
        name: "CRC-16/IBM-3740",
        poly: 0x1021,
        init: 0xFFFF,
        reflected: false,
        check: 0x29B1,
        oracle: &crc::CRC_16_IBM_3740,
    },
    Params {
        name: "CRC-16/UMTS (BUYPASS)",
        poly: 0x8005,
        init: 0x0000,
        reflected: false,
        check: 0xFEE8,
        oracle: &crc::CRC_16_UMTS,
    },
    Params {
        name: "CRC-16/KERMIT",
        poly: 0x1021,
        init: 0x0000,
        reflected: true,
        check: 0x2189,
        oracle: &crc::CRC_16_KERMIT,
    },
    Params {
        name: "CRC-16/SPI-FUJITSU (AUG-CCITT)",
        poly: 0x1021,
        init: 0x1D0F,
        reflected: false,
        check: 0xE5CC,
        oracle: &crc::CRC_16_SPI_FUJITSU,
    },
    Params {
        name: "CRC-16/MCRF4XX",
        poly: 0x1021,
        init: 0xFFFF,
        reflected: true,
        check: 0x6F91,
        oracle: &crc::CRC_16_MCRF4XX,
    },
    Params {
        name: "CRC-16/RIELLO",
        poly: 0x1021,
        init: 0xB2AA,
        reflected: true,
        check: 0x63D0,
        oracle: &crc::CRC_16_RIELLO,
    },
    Params {
        name: "CRC-16/CMS",
        poly: 0x8005,
        init: 0xFFFF,
        reflected: false,
        check: 0xAEE7,
        oracle: &crc::CRC_16_CMS,
    },
    Params {
        name: "CRC-16/DDS-110",
        poly: 0x8005,
        init: 0x800D,
        reflected: false,
        check: 0x9ECF,
        oracle: &crc::CRC_16_DDS_110,
    },
    Params {
        name: "CRC-16/T10-DIF",
        poly: 0x8BB7,
        init: 0x0000,
        reflected: false,
        check: 0xD0DB,
        oracle: &crc::CRC_16_T10_DIF,
    },
    Params {
        name: "CRC-16/CDMA2000",
        poly: 0xC867,
        init: 0xFFFF,
        reflected: false,
        check: 0x4C06,
        oracle: &crc::CRC_16_CDMA2000,
    },
    Params {
        name: "CRC-16/NRSC-5",
        poly: 0x080B,
        init: 0xFFFF,
        reflected: true,
        check: 0xA066,
        oracle: &crc::CRC_16_NRSC_5,
    },
];

/// A table-driven CRC-16 in the Rocksoft model (no final XOR), written
/// independently of the library's bit-at-a-time loops.
fn table_crc(poly: u16, init: u16, reflected: bool, data: &[u8]) -> u16 {
    let mut table = [0u16; 256];
    if reflected {
        let rpoly = poly.reverse_bits();
        for (n, slot) in table.iter_mut().enumerate() {
            let mut c = n as u16;
            for _ in 0..8 {
                c = if c & 1 == 1 { (c >> 1) ^ rpoly } else { c >> 1 };
            }
            *slot = c;
        }
        let mut reg = init.reverse_bits();
        for &b in data {
            reg = (reg >> 8) ^ table[usize::from((reg as u8) ^ b)];
        }
        reg
    } else {
        for (n, slot) in table.iter_mut().enumerate() {
            let mut c = (n as u16) << 8;
            for _ in 0..8 {
                c = if c & 0x8000 != 0 { (c << 1) ^ poly } else { c << 1 };
            }
            *slot = c;
        }
        let mut reg = init;
        for &b in data {
            reg = (reg << 8) ^ table[usize::from((reg >> 8) as u8 ^ b)];
        }
        reg
    }
}

/// LIN's CRC for a catalogue set: the seed is the register as loaded, so a
/// reflected set's `init` is bit-reversed.
fn lin_crc(p: &Params, data: &[u8]) -> Value {
    let seed = if p.reflected { p.init.reverse_bits() } else { p.init };
    let mode = i32::from(p.reflected);
    f("CRC", &[b(data), i(mode), i(i32::from(p.poly)), i(i32::from(seed))])
}

#[test]
fn crc_sets_match_their_published_check_values() {
    assert!(SETS.len() >= 5);
    for p in SETS {
        assert_eq!(p.oracle.poly, p.poly, "{}", p.name);
        assert_eq!(p.oracle.init, p.init, "{}", p.name);
        assert_eq!((p.oracle.refin, p.oracle.refout), (p.reflected, p.reflected), "{}", p.name);
        assert_eq!(p.oracle.xorout, 0, "{}", p.name);
        assert_eq!(p.oracle.check, p.check, "{}", p.name);
        assert_eq!(table_crc(p.poly, p.init, p.reflected, b"123456789"), p.check, "{}", p.name);
        assert_eq!(lin_crc(p, b"123456789"), i(i32::from(p.check)), "{}", p.name);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn crc_agrees_with_the_oracles(data in proptest::collection::vec(any::<u8>(), 0..80)) {
        for p in SETS {
            let want = table_crc(p.poly, p.init, p.reflected, &data);
            prop_assert_eq!(crc::Crc::<u16>::new(p.oracle).checksum(&data), want, "{}", p.name);
            prop_assert_eq!(lin_crc(p, &data), i(i32::from(want)), "{}", p.name);
        }
    }

    #[test]
    fn crc_any_polynomial_and_seed(
        data in proptest::collection::vec(any::<u8>(), 0..40),
        poly in any::<u16>(),
        seed in any::<u16>(),
        reflected in any::<bool>(),
    ) {
        let init = if reflected { seed.reverse_bits() } else { seed };
        let want = table_crc(poly, init, reflected, &data);
        let got = f("CRC", &[b(&data), i(i32::from(reflected)), i(i32::from(poly)), i(i32::from(seed))]);
        prop_assert_eq!(got, i(i32::from(want)));
        // Mode 1 is mode 0 on bit-reversed bytes, result and seed.
        let flipped: Vec<u8> = data.iter().map(|x| x.reverse_bits()).collect();
        if reflected {
            let plain = f("CRC", &[b(&flipped), i(0), i(i32::from(poly)), i(i32::from(seed.reverse_bits()))]);
            prop_assert_eq!(plain.as_int() as u16, want.reverse_bits());
        }
    }
}

// --------------------------------------------------------- EXTRACT/REPLACE

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn extract_after_replace_gives_the_value_back(
        buf in proptest::collection::vec(any::<u8>(), 0..12),
        p in -3..16_i32,
        v in any::<i32>(),
        x in any::<f32>(),
        order in -1..5_i32,
        bit in -1..9_i32,
        flag in any::<bool>(),
    ) {
        let n = buf.len() as i32;
        let fits = |size: i32| p >= 1 && p + size - 1 <= n;
        let valid_order = (0..=3).contains(&order);
        let cases: [(&str, &str, Vec<Value>, i32, Value); 7] = [
            ("REPLACE_INT8", "EXTRACT_INT8", vec![i(v)], 1, i(i32::from(v as i8))),
            ("REPLACE_UINT8", "EXTRACT_UINT8", vec![i(v)], 1, i(i32::from(v as u8))),
            ("REPLACE_INT16", "EXTRACT_INT16", vec![i(v), i(order)], 2, i(i32::from(v as i16))),
            ("REPLACE_UINT16", "EXTRACT_UINT16", vec![i(v), i(order)], 2, i(i32::from(v as u16))),
            ("REPLACE_INT32", "EXTRACT_INT32", vec![i(v), i(order)], 4, i(v)),
            ("REPLACE_REAL", "EXTRACT_REAL", vec![r(x), i(order)], 4, r(x)),
            ("REPLACE_BOOL", "EXTRACT_BOOL", vec![i(bit), Value::Bool(flag)], 1, Value::Bool(flag)),
        ];
        for (put, get, extra, size, want) in cases {
            let mut args = vec![b(&buf), i(p)];
            args.extend(extra.iter().cloned());
            let written = f(put, &args);
            let ok = fits(size)
                && (put.ends_with("INT8") || put == "REPLACE_BOOL" || valid_order)
                && (put != "REPLACE_BOOL" || (0..=7).contains(&bit));
            if !ok {
                prop_assert_eq!(&written, &null(), "{}", put);
                continue;
            }
            prop_assert_eq!(written.as_bytes().len(), buf.len());
            // Bytes outside the value are untouched.
            for (k, (old, new)) in buf.iter().zip(written.as_bytes()).enumerate() {
                let k = k as i32 + 1;
                if k < p || k >= p + size {
                    prop_assert_eq!(old, new);
                }
            }
            let mut get_args = vec![written, i(p)];
            match get {
                "EXTRACT_INT8" | "EXTRACT_UINT8" => {}
                "EXTRACT_BOOL" => get_args.push(i(bit)),
                _ => get_args.push(i(order)),
            }
            let got = f(get, &get_args);
            match (&got, &want) {
                (Value::Real(a), Value::Real(w)) => prop_assert_eq!(a.to_bits(), w.to_bits()),
                _ => prop_assert_eq!(&got, &want, "{}", get),
            }
        }
    }
}
