//! §10.2 action files, §12.10 actions, §12.11 transitions, §12.12 offsets.
use linc_conformance::{invalid, valid};

valid!(s10_2_several_actions_in_a_file, "§10.2", Action, "ACTION Fill\n  Dig_B.Out.Bit0 := 1;\nEND_ACTION\nACTION Drain : DIGACT\n  Out := 0;\n  Digout1 := In > 3;\nEND_ACTION;\n");
valid!(
    s10_2_action_for_the_action_block,
    "§10.2.3",
    NoDb,
    "ACTION Ramp : ACTION\n  Real1 := Real1 + Real2;\n  Bool1 := Real1 > Real3;\nEND_ACTION\n"
);
valid!(s10_2_action_without_header_is_named_after_file, "§10.2", Action, "Dig_B.Out.Bit0 := 1;\n");
valid!(
    s10_2_action_block_type_fields,
    "§10.2.3",
    NoDb,
    "ACTION Raw : RAW_COM\n  I1 := LEN(Rx_Value);\n  Tx_Value := FORMAT(\"04X\", I1);\nEND_ACTION\n"
);
invalid!(
    s10_2_action_block_type_unknown_field,
    "§10.2.3",
    NoDb,
    "ACTION Raw : RAW_COM\n  I9 := 1;\nEND_ACTION\n",
    ["E0100"]
);
invalid!(
    s10_2_1_action_name_too_long,
    "§10.2.1",
    Action,
    "ACTION Startup_1\n  Dig_B.Out.Bit0 := 1;\nEND_ACTION\n",
    ["E0014"]
);
invalid!(
    s10_2_1_action_name_digit_first,
    "§10.2.1",
    Action,
    "ACTION 1st\n  Dig_B.Out.Bit0 := 1;\nEND_ACTION\n",
    ["E0014"]
);
invalid!(s10_2_duplicate_action, "§10.2", Action, "ACTION Fill\nEND_ACTION\nACTION FILL\nEND_ACTION\n", ["E0117"]);
invalid!(s10_2_statement_outside_action, "§10.2", Action, "Dig_B.Out.Bit0 := 1;\nACTION Fill\nEND_ACTION\n", ["E0016"]);
invalid!(s10_2_unknown_block_type, "§10.2.3", Action, "ACTION Fill : NOSUCH\nEND_ACTION\n", ["E0116"]);
invalid!(s10_2_missing_end_action, "§10.2", Action, "ACTION Fill\n  Dig_B.Out.Bit0 := 1;\n", ["E0011"]);
valid!(s12_11_real_against_constant, "§12.11", Transition, "Recipe.a0 < 4");
valid!(s12_11_digital_true, "§12.11", Transition, "Dig_B.Out.Bit5");
valid!(s12_11_digital_false, "§12.11", Transition, "NOT Dig_B.Out.Bit5");
valid!(s12_11_step_time, "§12.11", Transition, "STEP6.T >= T#2m");
valid!(s12_11_step_time_seconds, "§12.11", Transition, "waitstep.t > 95");
valid!(s12_11_end_step_reached, "§12.11", Transition, "Act4_end.X");
valid!(s12_11_logical_combination, "§12.11", Transition, "Dig_B.Out.Bit5 AND (Rec.A0<4 OR Rec.A0>5) OR step6.T>=T#4s");
invalid!(s12_11_transition_must_be_truth_value, "§12.11", Transition, "Recipe.A0 + 1", ["E0119"]);
invalid!(s12_11_transition_is_one_expression, "§12.11", Transition, "Recipe.A0 < 1;", ["E0010"]);
valid!(s12_12_shift_register, "§12.12", Action, "FOR TC001:=0 to 6 DO (*Analogue shift register*)\n   Block_5.Val1{TC001}:=Block_5.Val1{TC001 + 1};\nEND_FOR;\nBlock_5.Val1{7}:=50;\n");
invalid!(
    s12_12_shift_register_as_printed,
    "§12.12",
    Action,
    "FOR TC001:=0 to 6 DO\n   Block_5.Val1{TC001}:=Block_5.Val1{TC001 + 1};\nEND_FOR;\nBlock_5.Val1{7}:=50\n",
    ["W0001"]
);
valid!(
    s12_12_offset_then_bit,
    "§12.12",
    Action,
    "Dig_A.Out{1}.Bit0 := 1;\nDig_A.Out{Recipe.N0}.Bit0{3} := Dig_A.Out.Bit0{Recipe.N1};\n"
);
valid!(
    s12_12_offsets_on_action_block_fields,
    "§12.12",
    NoDb,
    "ACTION shift : AN_CONN\n  PV1{3} := PV5{3};\nEND_ACTION\n"
);
invalid!(s12_12_last_bit_cannot_be_base, "§12.12", Action, "Dig_A.Out.Bit7{0} := 1;\n", ["E0109"]);
invalid!(
    s12_12_constant_bit_offset_beyond_last_bit,
    "§12.12",
    Action,
    "Dig_A.Out.Bit5{3} := 1;\nDig_A.Out.Bit5{-1} := 1;\nDig_A.Out.Bit5{2} := 1;\n",
    ["E0109", "E0109"]
);
invalid!(s12_12_base_must_start_a_run, "§12.12", Action, "TIC_100.Mode{1} := 1;\n", ["E0109"]);
invalid!(
    s12_12_constant_offset_out_of_run,
    "§12.12",
    Action,
    "Block_5.Val1{8} := 1;\nBlock_5.Val8{1} := 1;\n",
    ["E0109", "E0109"]
);
invalid!(s12_12_offset_must_be_a_number, "§12.12", Action, "Block_5.Val1{'two'} := 1;\n", ["E0118"]);
invalid!(s12_12_one_offset_per_name_part, "§12.12", Action, "Block_5.Val1{1}{2} := 1;\n", ["E0015"]);
invalid!(s12_12_constant_offset_onto_read_only_field, "§12.12", Action, "TIC_100.PV{1} := 1;\n", ["E0108"]);
