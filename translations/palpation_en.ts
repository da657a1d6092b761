<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="en_US">
<context>
    <name>DevicePanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="39"/>
        <source>Thumb</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="39"/>
        <source>Index</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="40"/>
        <source>Middle</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="40"/>
        <source>Ring</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="41"/>
        <source>Little</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ForcePlots</name>
    <message>
        <location filename="../ui/force_plots.cpp" line="20"/>
        <source>thumb</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="20"/>
        <source>index</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="21"/>
        <source>middle</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="21"/>
        <source>ring</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="22"/>
        <source>little</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>QObject</name>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="43"/>
        <source>Undo: %1</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::DevicePanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="329"/>
        <source>Simulated HandHIRO (scripted palpation)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="330"/>
        <source>Mouse palpation (no robot)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="331"/>
        <source>Device</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="332"/>
        <source>HandHIRO address</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="333"/>
        <source>Loop jitter</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="334"/>
        <source>The HandHIRO network link is chosen at start: palpation-trainer --device emulator, or --device handhiro --robot ADDRESS:PORT.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="347"/>
        <source>attached</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="347"/>
        <source>released</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="349"/>
        <source>%1 us (max over 0.5 s)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::ForcePlots</name>
    <message>
        <location filename="../ui/force_plots.cpp" line="77"/>
        <source>Export plot as PNG</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="77"/>
        <source>PNG images (*.png)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="81"/>
        <source>Export forces as CSV</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="81"/>
        <source>CSV files (*.csv)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="88"/>
        <source>|F| vs time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="89"/>
        <source>Fz vs time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="90"/>
        <source>Fz vs x (Fig. 6)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="91"/>
        <source>Force magnitude per finger (N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="92"/>
        <source>Fz per finger (N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="93"/>
        <source>Fz (N) against finger x (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="100"/>
        <source>Resume</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="100"/>
        <source>Pause</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="101"/>
        <source>Export PNG...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="102"/>
        <source>Export CSV...</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::MainWindow</name>
    <message>
        <location filename="../ui/main_window.cpp" line="98"/>
        <source>Mouse palpation: move over the breast; the wheel or a downward drag presses the fingertip in.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="108"/>
        <source>No element lies inside that shape: nothing added.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="152"/>
        <source>Save screenshot</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="152"/>
        <source>PNG images (*.png)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="182"/>
        <location filename="../ui/main_window.cpp" line="255"/>
        <source>Stereo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="192"/>
        <source>Eye separation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="192"/>
        <source>Eye angle (degrees):</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="244"/>
        <source>Palpation Trainer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="245"/>
        <source>&amp;File</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="246"/>
        <source>Save &amp;screenshot...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="247"/>
        <source>&amp;Quit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="248"/>
        <source>&amp;Edit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="249"/>
        <source>Undo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="250"/>
        <source>Redo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="251"/>
        <source>&amp;View</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="252"/>
        <source>Camera</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="253"/>
        <source>Oblique</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="253"/>
        <source>Top</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="253"/>
        <source>Side</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="253"/>
        <source>Front</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="256"/>
        <source>Mono</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="256"/>
        <source>Anaglyph (red/cyan)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="256"/>
        <source>Side by side</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="256"/>
        <source>Interlaced</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="256"/>
        <source>Quad-buffer (shutter glasses)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="258"/>
        <source>Eye separation...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="259"/>
        <source>Mirrored (half-mirror display)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="260"/>
        <source>Displacement colour map</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="261"/>
        <source>Show tumours</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="262"/>
        <source>Panels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="263"/>
        <source>&amp;Mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="264"/>
        <source>Trainee mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="265"/>
        <source>Instructor mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="266"/>
        <source>Tools</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="267"/>
        <source>Camera / scripted hand</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="268"/>
        <source>Palpate with the mouse</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="269"/>
        <source>Patient</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="270"/>
        <source>Tumours</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="271"/>
        <source>Forces</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="272"/>
        <source>Simulation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="273"/>
        <source>Device</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="335"/>
        <source>%1 nodes, %2 tetrahedra</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="368"/>
        <source>Backend: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="369"/>
        <source>Simulation: %1 Hz</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="370"/>
        <source>Haptic: %1 Hz</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="372"/>
        <source>mouse</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="373"/>
        <source>simulated HandHIRO</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="374"/>
        <source>Device: %1, %2</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="374"/>
        <source>connected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="374"/>
        <source>not connected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="375"/>
        <source>View: %1 fps</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::PatientPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="68"/>
        <source>Breast phantom (paper)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="69"/>
        <source>Box phantom</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="70"/>
        <source>Coarse (about 1,000 nodes, real time on a CPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="71"/>
        <source>Paper (about 9,100 nodes, GPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="72"/>
        <source>Fine (GPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="73"/>
        <source>Patient</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="74"/>
        <source>Resolution</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="75"/>
        <source>Tissue Young&apos;s modulus</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="76"/>
        <source>Poisson ratio</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="77"/>
        <source>Load patient</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="78"/>
        <source>Built-in phantoms; the patient library comes with a later version.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::SimulationPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="272"/>
        <source>Backend</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="273"/>
        <source>CG tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="274"/>
        <source>CG max. iterations</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="275"/>
        <source>State</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="276"/>
        <source>Step time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="277"/>
        <source>CG iterations</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="278"/>
        <source>Simulation rate</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="279"/>
        <source>Haptic rate</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="280"/>
        <source>Apply solver settings</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="281"/>
        <source>A backend change takes effect when the patient is (re)loaded.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="291"/>
        <source>%1 ms</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="293"/>
        <location filename="../ui/panels.cpp" line="294"/>
        <source>%1 Hz</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::TumourEditor</name>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="11"/>
        <source>Tumour (paper, 107 kPa)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="11"/>
        <source>Ueda et al., paper section 4.1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="12"/>
        <source>Invasive ductal carcinoma (Krouskop, 5%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="12"/>
        <source>Krouskop et al. 1998: 93-112 kPa at 5% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="13"/>
        <source>Invasive ductal carcinoma (Krouskop, 20%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="13"/>
        <source>Krouskop et al. 1998: 460-558 kPa at 20% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="14"/>
        <source>Fibrous tissue (Krouskop, 5%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="14"/>
        <source>Krouskop et al. 1998: 96-116 kPa at 5% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="15"/>
        <source>DCIS (Krouskop, 20%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="15"/>
        <source>Krouskop et al. 1998: 291-307 kPa at 20% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="16"/>
        <source>Fibroglandular (Krouskop, 5%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="16"/>
        <source>Krouskop et al. 1998: 28-35 kPa at 5% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="17"/>
        <source>IDC high grade (Samani)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="17"/>
        <source>Samani et al. 2007: 10-43 kPa by grade, small strain</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="18"/>
        <source>Fibroadenoma (Samani, 2x fat)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="18"/>
        <source>Samani et al. 2007: about 6.4 kPa</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="71"/>
        <source>Patient&apos;s tumour</source>
        <translation type="unfinished"></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/tumour_editor.cpp" line="78"/>
        <source>%1 (%n elements)</source>
        <translation><numerusform>%1 (%n element)</numerusform><numerusform>%1 (%n elements)</numerusform></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="120"/>
        <source>%1 at (%2, %3, %4) cm, %5 kPa</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="121"/>
        <source>Sphere</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="121"/>
        <source>Ellipsoid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="126"/>
        <source>Add tumour: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="139"/>
        <source>Remove tumour: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="164"/>
        <source>Erase</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="164"/>
        <source>Paint</source>
        <translation type="unfinished"></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/tumour_editor.cpp" line="177"/>
        <source>Erase stroke (%n elements)</source>
        <translation><numerusform>Erase stroke (%n element)</numerusform><numerusform>Erase stroke (%n elements)</numerusform></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/tumour_editor.cpp" line="180"/>
        <source>Paint stroke (%n elements)</source>
        <translation><numerusform>Paint stroke (%n element)</numerusform><numerusform>Paint stroke (%n elements)</numerusform></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="181"/>
        <source>Painted tumour %1, %2 kPa</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::TumourPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="186"/>
        <location filename="../ui/panels.cpp" line="212"/>
        <source>Source: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="213"/>
        <source>Preset</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="214"/>
        <source>Stiffness</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="215"/>
        <source>Add by shape</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="216"/>
        <source>Sphere</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="217"/>
        <source>Ellipsoid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="218"/>
        <source>Shape</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="219"/>
        <source>Centre x, y, z</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="220"/>
        <source>Radius (x, y, z)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="221"/>
        <source>Add tumour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="222"/>
        <source>Remove selected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="223"/>
        <source>Brush</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="224"/>
        <source>Radius</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="225"/>
        <source>Depth below the skin</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="226"/>
        <source>Paint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="227"/>
        <source>Erase</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="228"/>
        <source>Drag on the breast to paint tumour tissue (one undo step per stroke)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="229"/>
        <source>Drag on the breast to restore healthy tissue</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="230"/>
        <source>Undo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="231"/>
        <source>Redo</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::VtkView</name>
    <message>
        <location filename="../ui/vtk_view.cpp" line="287"/>
        <source>Quad-buffer stereo is not available: this display&apos;s OpenGL context has no stereo buffers (needs a stereo-capable GPU, driver and display). Use anaglyph, side-by-side or interlaced.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
</TS>
