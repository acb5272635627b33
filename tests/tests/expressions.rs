//! §12.5 expressions and §12.6 operators and their precedence.
use linc_conformance::{invalid, valid};

valid!(s12_5_arithmetical, "§12.5", Transition, "(Block_5.PV + 3.5) / Const.A7 + Const.A6 > 0");
valid!(s12_5_cos_power, "§12.5", Transition, "COS(Block_6.PV)**1.5 > 0.5");
valid!(s12_5_bitwise_and, "§12.5", Transition, "Dig_A.Out AND 64");
valid!(s12_5_logical_compare, "§12.5", Transition, "Recipe.A0 < 4");
valid!(s12_5_bit_equality, "§12.5", Transition, "Dig_B.Out.Bit5 = Dig_A.Out.Bit3");
valid!(s12_5_step_time, "§12.5", Transition, "STEP3.T >= T#4m");
valid!(s12_5_offset_expression, "§12.5", Action, "ACTION demo : GUIDEACT\n  A1 := A0{7};\n  N := 6;\n  Dig_A.Out.Bit0 := [Word 3.Bit4]{N};\n  Dig_A.Out.Bit1 := [Word 1]{N/2}.Bit4{N};\nEND_ACTION\n");
valid!(s12_5_nested_brackets, "§12.5", Action, "Recipe.A0 := ((((Recipe.A1 + 1)) * (2 - (Recipe.A2))));\n");
valid!(s12_6_subtraction_is_left_associative, "§12.6", Action, "Recipe.N0 := 10 - 2 - 3;\n");
valid!(s12_6_division_is_left_associative, "§12.6", Action, "Recipe.N0 := 100 / 10 / 5;\n");
valid!(s12_6_power_is_left_associative, "§12.6", Action, "Recipe.A0 := 2 ** 3 ** 2;\n");
// The guide's table gives `*`, `/`, `MOD`, `+` and `-` a row each; linc,
// as IEC 61131-3, gives `* / MOD` one level and `+ -` another, each left
// to right (decision 17): `10 - 2 + 3` is 11, not 5, and `12 / 3 * 2` is
// 8, not 2.
valid!(s12_6_add_and_subtract_share_a_level, "§12.6", Action, "Recipe.N0 := 10 - 2 + 3;\n");
valid!(s12_6_multiply_and_divide_share_a_level, "§12.6", Action, "Recipe.N0 := 12 / 3 * 2;\n");
valid!(s12_6_mod_and_divide_share_a_level, "§12.6", Action, "Recipe.N0 := 10 MOD 4 / 2;\n");
valid!(s12_6_negation_binds_tighter_than_power, "§12.6", Action, "Recipe.A0 := -Recipe.A1 ** 2;\n");
valid!(s12_6_power_binds_tighter_than_multiply, "§12.6", Action, "Recipe.A0 := 2 * Recipe.A1 ** 2;\n");
valid!(s12_6_multiply_before_add, "§12.6", Action, "Recipe.N0 := 1 + 2 * 3 MOD 4;\n");
valid!(s12_6_arithmetic_before_comparison, "§12.6", Transition, "Recipe.A0 + 1 < Recipe.A1 * 2");
valid!(
    s12_6_comparison_before_and_xor_or,
    "§12.6",
    Transition,
    "Recipe.A0 < 1 OR Recipe.A1 > 2 XOR Recipe.A2 = 3 AND Recipe.A3 <> 4"
);
valid!(s12_6_not_binds_tightest, "§12.6", Transition, "NOT Dig_A.Out.Bit0 AND Dig_A.Out.Bit1");
valid!(s12_6_not_of_bracket, "§12.6", Transition, "NOT(Dig_A.Out.Bit0 OR Dig_A.Out.Bit1)");
valid!(s12_6_all_comparisons, "§12.6", Action, "Dig_B.Out.Bit0 := Recipe.A0 = 1;\nDig_B.Out.Bit1 := Recipe.A0 < 1;\nDig_B.Out.Bit2 := Recipe.A0 > 1;\nDig_B.Out.Bit3 := Recipe.A0 <= 1;\nDig_B.Out.Bit4 := Recipe.A0 >= 1;\nDig_B.Out.Bit5 := Recipe.A0 <> 1;\n");
valid!(s12_6_mod_on_integers, "§12.6", Action, "Recipe.N0 := (Recipe.N1)MOD(Recipe.N2);\n");
invalid!(s12_6_mod_on_reals, "§12.6", Action, "Recipe.N0 := Recipe.A1 MOD 2;\n", ["E0105"]);
valid!(s12_6_string_comparison, "§12.6", Transition, "PIC_004.Mode = \"cascade\"");
invalid!(s12_6_enum_comparison_checks_value, "§12.6", Transition, "PIC_004.Mode = \"CASCADED\"", ["E0104"]);
invalid!(s12_6_string_plus_number, "§12.6", Action, "Recipe.A0 := Raw1.Rx_Value + 1;\n", ["E0114"]);
invalid!(s12_6_and_on_reals, "§12.6", Transition, "Recipe.A0 AND 1", ["E0114"]);
invalid!(s12_6_unbalanced_bracket, "§12.6", Action, "Recipe.A0 := (Recipe.A1 + 2;\n", ["E0010"]);

/// The values of decision 17's groupings, run: a table row per level would
/// give 5, 2, 0 and 7 instead.
#[test]
fn s12_6_one_level_for_multiplicative_and_one_for_additive_operators() {
    let src =
        "Recipe.N0 := 10 - 2 + 3;\nRecipe.N1 := 12 / 3 * 2;\nRecipe.N2 := 10 MOD 4 / 2;\nRecipe.N3 := 7 MOD 4 * 2;\n\
               Recipe.A0 := 1.0 - 0.5 + 0.25;\nRecipe.A1 := 8.0 / 4.0 * 2.0;\n";
    let r = linc_conformance::exec::run(src);
    assert_eq!(r.error, None);
    let got = ["Recipe.N0", "Recipe.N1", "Recipe.N2", "Recipe.N3", "Recipe.A0", "Recipe.A1"].map(|p| r.get(p));
    assert_eq!(got, ["11", "8", "1", "6", "0.75", "4.0"]);
}
