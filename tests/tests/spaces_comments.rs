//! §12 introduction, §12.2 spaces and §12.3 comments.
use linc_conformance::{invalid, valid};

valid!(s12_intro_example, "§12", Action, "(*ADJUST TEMP SETPOINT*) TIC_100.SL:= REC1.A4;(*A statement*)\n");
valid!(s12_intro_expression, "§12", Transition, "Dig_A.Out AND 64 (*An expression*)");
valid!(s12_2_1_mandatory_spaces, "§12.2.1", Transition, "LEV.OP>15 AND TEMP.OP<55.5");
invalid!(s12_2_1_word_operator_glued_to_name, "§12.2.1", Transition, "LEV.OP>15 ANDTEMP.OP<55.5", ["E0007"]);
invalid!(s12_2_1_word_operator_glued_in_statement, "§12.2.1", Action, "Dig_B.Out := Dig_A.Out ANDB;\n", ["E0007"]);
valid!(
    s12_2_1_brackets_separate_word_operators,
    "§12.2.1",
    Action,
    "Recipe.N0 := (Recipe.N1)MOD(Recipe.N2);\nDig_B.Out.Bit0 := (Dig_A.Out.Bit1)AND(Dig_A.Out.Bit2);\n"
);
invalid!(s12_2_2_illegal_spaces_in_names, "§12.2.2", Action, "HEAT_PID. SL:=REC1. A3;\n", ["E0004", "E0004"]);
invalid!(s12_2_2_space_before_dot, "§12.2.2", Action, "HEAT_PID .SL := 1;\n", ["E0004"]);
invalid!(s12_2_2_space_inside_assign_operator, "§12.2.2", Action, "TIC_100.PV : = 45.5;\n", ["E0004"]);
invalid!(
    s12_2_2_space_inside_power_and_compare,
    "§12.2.2",
    Action,
    "Recipe.A0 := Recipe.A1 * * 2;\nDig_A.Out.Bit0 := Recipe.A1 < = 2;\n",
    ["E0004", "E0004"]
);
invalid!(s12_2_2_space_inside_real_constant, "§12.2.2", Action, "TIC_100.PV := 45. 5;\n", ["E0004"]);
valid!(
    s12_2_3_optional_spaces,
    "§12.2.3",
    Action,
    "TIC_100.PV:=45.5;\nTIC_100.PV := 45.5;\n   TIC_100.PV\t:=\t45.5 ;\n"
);
valid!(
    s12_3_comments_around_statement,
    "§12.3",
    Action,
    "(*ADJUST TEMP SETPOINT*) TIC_100.SL:= REC1.A4;(*RECIPE #5*)\n"
);
valid!(s12_3_comment_where_a_space_may_go, "§12.3", Action, "TIC_100.SL(*sp*):=(*value*)REC1.A4(*end*);\n");
valid!(s12_3_comment_over_lines, "§12.3", Action, "(* a comment\n   over two lines *)\nTIC_100.SL := 1;\n");
invalid!(s12_3_unclosed_comment, "§12.3", Action, "TIC_100.SL := 1; (* never closed\nTIC_100.SL := 2;\n", ["E0003"]);
invalid!(s12_typographic_quotes, "§12.9", Action, "TIC_100.SL := SCAN(\u{201C}X\u{201D}, Raw1.Rx_Value);\n", ["E0001"]);
invalid!(s12_2_2_comment_inside_a_name, "§12.2.2", Action, "TIC_100(*c*).SL := 1;\n", ["E0004"]);
