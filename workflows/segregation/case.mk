# Brazil-nut segregation (thesis §4.5): the README's demo.
#   make -f Makefile.cases segregation        generate, settle, vibrate 94 cycles (the thesis's span),
#                                             post-process, report and plot (a few minutes)
#   make -f Makefile.cases segregation-long   continue to 1,000 cycles and report the rise again
SEG_DIR := $(OUT)/segregation
SEG_SCENE := workflows/segregation/scene.toml
SEG_REPORT := $(PYTHON) scripts/segregation_report.py --intruder 0 --frequency 20

$(SEG_DIR)/settled.h5: $(SEG_SCENE) $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $(SEG_SCENE) --out $@

# The large sphere (id 0) is tracked 45 times per cycle; one VTK frame per cycle at the same phase.
$(SEG_DIR)/vibrated.h5 $(SEG_DIR)/intruder.csv &: $(SEG_SCENE) $(SEG_DIR)/settled.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(SEG_SCENE) --stage vibrate --in $(SEG_DIR)/settled.h5 --out $(SEG_DIR)/vibrated.h5 \
	  --track $(SEG_DIR)/intruder.csv --track-ids 0 --track-every 100 --vtk $(SEG_DIR)/vtk \
	  --checkpoint-every 50000 --restart

# Particles coloured by their displacement over the span, and the displacement field on an 8 mm grid
# (kernel width one small diameter): open in ParaView with the VTK series in vtk/.
$(SEG_DIR)/displacement.vtu $(SEG_DIR)/fields.vti &: $(SEG_DIR)/settled.h5 $(SEG_DIR)/vibrated.h5 $(BIN)/post-macro
	$(BIN)/post-macro --reference $(SEG_DIR)/settled.h5 --in $(SEG_DIR)/vibrated.h5 --vtk $(SEG_DIR)/displacement.vtu \
	  --grid $(SEG_DIR)/fields.vti --cell 0.008 --width 0.008

$(SEG_DIR)/segregation.png $(SEG_DIR)/summary.csv $(SEG_DIR)/convection.csv &: $(SEG_DIR)/settled.h5 $(SEG_DIR)/vibrated.h5 \
    $(SEG_DIR)/intruder.csv scripts/segregation_report.py scripts/post_table.py
	$(SEG_REPORT) --start $(SEG_DIR)/settled.h5 --span $(SEG_DIR)/vibrated.h5 --track $(SEG_DIR)/intruder.csv \
	  --summary $(SEG_DIR)/summary.csv --convection $(SEG_DIR)/convection.csv --png $(SEG_DIR)/segregation.png

$(SEG_DIR)/long.h5 $(SEG_DIR)/intruder_long.csv &: $(SEG_SCENE) $(SEG_DIR)/vibrated.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(SEG_SCENE) --stage continue --in $(SEG_DIR)/vibrated.h5 --out $(SEG_DIR)/long.h5 \
	  --track $(SEG_DIR)/intruder_long.csv --track-ids 0 --track-every 100 --vtk $(SEG_DIR)/vtk \
	  --checkpoint-every 200000 --restart

$(SEG_DIR)/segregation_long.png $(SEG_DIR)/summary_long.csv $(SEG_DIR)/convection_long.csv &: $(SEG_DIR)/long.h5 \
    $(SEG_DIR)/intruder.csv $(SEG_DIR)/intruder_long.csv scripts/segregation_report.py scripts/post_table.py
	$(SEG_REPORT) --start $(SEG_DIR)/settled.h5 --span $(SEG_DIR)/vibrated.h5 --end $(SEG_DIR)/long.h5 \
	  --track $(SEG_DIR)/intruder.csv $(SEG_DIR)/intruder_long.csv \
	  --summary $(SEG_DIR)/summary_long.csv --convection $(SEG_DIR)/convection_long.csv --png $(SEG_DIR)/segregation_long.png

.PHONY: segregation segregation-outputs segregation-long segregation-long-outputs
segregation: build
	@$(MAKE) --no-print-directory -f $(SELF) segregation-outputs
	@echo "segregation: VTK series $(SEG_DIR)/vtk/vibrate_particles.pvd (walls: vibrate_walls.pvd), displacement $(SEG_DIR)/displacement.vtu, fields $(SEG_DIR)/fields.vti"
	@echo "segregation: plot $(SEG_DIR)/segregation.png, figures $(SEG_DIR)/summary.csv, convection profile $(SEG_DIR)/convection.csv"
segregation-outputs: $(SEG_DIR)/segregation.png $(SEG_DIR)/displacement.vtu
segregation-long: build
	@$(MAKE) --no-print-directory -f $(SELF) segregation-long-outputs
	@echo "segregation-long: plot $(SEG_DIR)/segregation_long.png, figures $(SEG_DIR)/summary_long.csv"
segregation-long-outputs: $(SEG_DIR)/segregation_long.png
CASES += segregation
