//! §12.9 constants.
use linc_conformance::{invalid, valid};

valid!(s12_9_integers, "§12.9", Action, "Recipe.N0 := 45;\nRecipe.N1 := -12345;\nRecipe.N2 := 16#FF + 16#00ff + 16#03e8 + 16#03E8;\nRecipe.N3 := 2#1100 + 2#0010;\n");
valid!(
    s12_9_integers_are_clipped,
    "§12.9",
    Action,
    "Recipe.N0 := 99999999999;\nRecipe.N1 := -2147483648;\nRecipe.N2 := -99999999999;\nRecipe.N3 := 16#FFFFFFFFFF;\n"
);
valid!(s12_9_reals, "§12.9", Action, "Recipe.A0 := 3.6;\nRecipe.A1 := -0.0033;\nRecipe.A2 := 1.5E3;\n");
valid!(s12_9_times, "§12.9", Action, "Recipe.A0 := T#3s;\nRecipe.A1 := T#4m13.0s;\nRecipe.A2 := T#5.6h;\nRecipe.A3 := T#1d12.2h;\nRecipe.A4 := t#2M;\nRecipe.A3:=T#1h;\n");
invalid!(s12_9_bad_time_unit, "§12.9", Action, "Recipe.A0 := T#5x;\n", ["E0009"]);
invalid!(s12_9_bad_hex_digit, "§12.9", Action, "Recipe.N0 := 16#FG;\nRecipe.N1 := 2#102;\n", ["E0008", "E0008"]);
valid!(
    s12_9_strings,
    "§12.9",
    Action,
    "PIC_004.Mode := \"MANUAL\";\nSFC_CON.FileName := \"P\";\nSFC_CON.FileName := 'it$'s';\n"
);
valid!(s12_9_string_constant_fields, "§12.9", Action, "pid1.mode:=\"Manual\";\nTimeDate.Date1:=\"18/07/09\";\nSFC_CON.FileName:=\"Batch1\";\nTimeDate.CurrTime:=\"14:22:18\";\nWIDESTR2.VAL1:=\"r$F4le\";\nRAW_COM.Buffer1:=\"a$62c\";\n");
invalid!(s12_9_block_type_name_too_long, "§12.9", Action, "WIDESTR24S.VAL1:=\"r$F4le\";\n", ["E0005"]);
invalid!(s12_9_unclosed_string, "§12.9", Action, "SFC_CON.FileName := 'Batch1;\n", ["E0002", "W0001"]);
invalid!(s12_9_string_into_numeric_field, "§12.9", Action, "PIC_004.PV := \"35.5\";\n", ["E0103"]);
invalid!(s12_9_number_into_string_field, "§12.9", Action, "SFC_CON.FileName := 35;\n", ["E0103"]);
invalid!(s12_9_number_into_enum_field, "§12.9", Action, "PIC_004.Mode := 2;\n", ["E0103"]);
invalid!(s12_9_unknown_enum_value, "§12.9", Action, "PIC_004.Mode := \"AUTOMATIC\";\n", ["E0104"]);
valid!(s12_9_booleans, "§12.11", Action, "Dig_A.Out.Bit0 := TRUE;\nDig_A.Out.Bit1 := false;\n");
