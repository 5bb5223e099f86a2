// The shipped mc-table (profiles/data/mc_table.bin) compiled into the library as bytes:
// the assembler's .incbin copies the file into .rodata between two symbols, so the data
// needs no file at run time and no generated source. CMake passes the file's absolute
// path as SSS_MC_TABLE_PATH and lists the file as a dependency of this object, so a
// regenerated table rebuilds the library.
#ifndef SSS_MC_TABLE_PATH
#error "SSS_MC_TABLE_PATH must name profiles/data/mc_table.bin (set by profiles/CMakeLists.txt)"
#endif

__asm__(
    ".pushsection .rodata\n"
    ".balign 16\n"
    ".globl sss_mc_table_begin\n"
    ".hidden sss_mc_table_begin\n"
    ".type sss_mc_table_begin, @object\n"
    "sss_mc_table_begin:\n"
    ".incbin \"" SSS_MC_TABLE_PATH "\"\n"
    ".globl sss_mc_table_end\n"
    ".hidden sss_mc_table_end\n"
    "sss_mc_table_end:\n"
    ".byte 0\n"
    ".popsection\n");
