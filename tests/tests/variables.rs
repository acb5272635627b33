//! §12.7 variables and §12.8 identifiers.
use linc_conformance::{invalid, valid};

valid!(
    s12_7_1_database_name_forms,
    "§12.7.1",
    Action,
    "PIC_004.PV := 1;\nDig_A.Out.Bit3 := 1;\nTIC_100.Options := 3;\nDig_B.Out.Bit0 := ANIN_005.Alarms.HiLevel;\n"
);
valid!(s12_7_1_names_ignore_case, "§12.7.1", Action, "Dig_A.OUT.BIT3 := dig_a.out.bit3;\npic_004.pv := PIC_004.Pv;\n");
invalid!(s12_7_1_unknown_block, "§12.7.1", Action, "PIC_999.PV := 1;\n", ["E0100"]);
invalid!(s12_7_1_unknown_field, "§12.7.1", Action, "PIC_004.PVX := 1;\n", ["E0101"]);
invalid!(s12_7_1_bit_out_of_range, "§12.7.1", Action, "Dig_A.Out.Bit8 := 1;\n", ["E0102"]);
invalid!(s12_7_1_sub_field_of_a_real, "§12.7.1", Action, "PIC_004.PV.Bit0 := 1;\n", ["E0102"]);
invalid!(s12_7_1_block_alone_is_not_a_value, "§12.7.1", Action, "PIC_004.PV := PIC_004;\n", ["E0115"]);
invalid!(s12_7_1_read_only_field, "§12.7.1", Action, "PIC_004.SP := 1;\n", ["E0108"]);
valid!(s18_alarm_suppression, "§18.3", Action, "ANIN_005.Alarms.HiLevel.Suppress := 3600;\nANIN_005.Alarms.Suppress := -1;\nRecipe.N0 := ANIN_005.Alarms.HiLevel.Suppress;\n");
invalid!(s18_alarm_state_is_read_only, "§18.3", Action, "ANIN_005.Alarms.HiLevel := 0;\n", ["E0108"]);
invalid!(s18_unknown_alarm, "§18.3", Action, "Dig_A.Out.Bit0 := ANIN_005.Alarms.HiHiHi;\n", ["E0102"]);
invalid!(s18_alarm_list_is_not_a_value, "§18.3", Action, "Recipe.N0 := ANIN_005.Alarms;\n", ["E0115"]);
valid!(
    s12_7_2_bitfields,
    "§12.7.2",
    Action,
    "Dig_A.Out:=96;\nDig_A.Out := 2#01100000;\nDig_B.Out.Bit5 := Dig_A.Out.Bit6;\n"
);
valid!(s12_7_3_aliases, "§12.7.3", Action, "avg := avg + 1;\nAVG := f{2};\n");
valid!(s12_7_4_step_variables, "§12.7.4", Sequence, "Recipe.A0 := STEP5.T;\nDig_A.Out.Bit0 := END_STEP.X;\n");
invalid!(s12_7_4_step_variables_outside_sequences, "§12.7.4", Action, "Recipe.A0 := STEP5.T;\n", ["E0113"]);
invalid!(s12_7_4_step_variables_are_read_only, "§12.7.4", Sequence, "STEP5.T := 0;\n", ["E0108"]);
valid!(
    s12_8_1_valid_identifiers,
    "§12.8.1",
    NoDb,
    "A1.PV := act_4.PV + FlowMetr.PV + _Pump.PV + X__3Y.PV + z567931.PV;\n"
);
invalid!(s12_8_2_digit_first, "§12.8.2", NoDb, "1A.PV := 1;\n", ["E0006"]);
invalid!(s12_8_2_space_in_name, "§12.8.2", NoDb, "Pump 3.PV := 1;\n", ["E0010"]);
invalid!(s12_8_2_minus_sign, "§12.8.2", NoDb, "Flow-Mtr.PV := 1;\n", ["E0010"]);
invalid!(s12_8_2_multiply_sign, "§12.8.2", NoDb, "x*y*z.OP := 1;\n", ["E0010"]);
invalid!(s12_8_2_number_first, "§12.8.2", NoDb, "6366.MN := 1;\n", ["E0006"]);
invalid!(s12_8_2_dot_in_identifier, "§12.8.2", NoDb, "T1.2 := 1;\n", ["E0006"]);
invalid!(s12_8_2_too_long, "§12.8.2", NoDb, "Pulserate.PV := 1;\n", ["E0005"]);
invalid!(s12_8_2_too_long_field, "§12.8.2", Action, "Raw1.Rx_Values := 'a';\n", ["E0005"]);
valid!(s12_8_2_bracketed_names, "§12.8.2", Action, "[6366.MN] := 1;\n[DG_CONN3.W Field2.Bit6] := [x*y*z.OP] > 2;\n");
invalid!(s12_8_2_bracketed_name_still_resolved, "§12.8.2", Action, "[6366.MX] := 1;\n", ["E0101"]);
invalid!(s12_8_2_unclosed_bracket, "§12.8.2", Action, "[6366.MN := 1;\n", ["E0013", "E0011"]);
