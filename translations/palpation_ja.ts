<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="ja_JP">
<context>
    <name>DevicePanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="39"/>
        <source>Thumb</source>
        <translation>親指</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="39"/>
        <source>Index</source>
        <translation>人差し指</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="40"/>
        <source>Middle</source>
        <translation>中指</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="40"/>
        <source>Ring</source>
        <translation>薬指</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="41"/>
        <source>Little</source>
        <translation>小指</translation>
    </message>
</context>
<context>
    <name>ForcePlots</name>
    <message>
        <location filename="../ui/force_plots.cpp" line="20"/>
        <source>thumb</source>
        <translation>親指</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="20"/>
        <source>index</source>
        <translation>人差し指</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="21"/>
        <source>middle</source>
        <translation>中指</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="21"/>
        <source>ring</source>
        <translation>薬指</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="22"/>
        <source>little</source>
        <translation>小指</translation>
    </message>
</context>
<context>
    <name>QObject</name>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="43"/>
        <source>Undo: %1</source>
        <translation>取り消し: %1</translation>
    </message>
</context>
<context>
    <name>palpation::ui::DevicePanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="329"/>
        <source>Simulated HandHIRO (scripted palpation)</source>
        <translation>シミュレーションの HandHIRO（自動触診）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="330"/>
        <source>Mouse palpation (no robot)</source>
        <translation>マウス触診（ロボットなし）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="331"/>
        <source>Device</source>
        <translation>デバイス</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="332"/>
        <source>HandHIRO address</source>
        <translation>HandHIRO アドレス</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="333"/>
        <source>Loop jitter</source>
        <translation>ループのジッタ</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="334"/>
        <source>The HandHIRO network link is chosen at start: palpation-trainer --device emulator, or --device handhiro --robot ADDRESS:PORT.</source>
        <translation>HandHIRO のネットワーク接続は起動時に選びます: palpation-trainer --device emulator、または --device handhiro --robot アドレス:ポート</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="347"/>
        <source>attached</source>
        <translation>装着</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="347"/>
        <source>released</source>
        <translation>解放</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="349"/>
        <source>%1 us (max over 0.5 s)</source>
        <translation>%1 µs（0.5 秒間の最大）</translation>
    </message>
</context>
<context>
    <name>palpation::ui::ForcePlots</name>
    <message>
        <location filename="../ui/force_plots.cpp" line="77"/>
        <source>Export plot as PNG</source>
        <translation>グラフを PNG で出力</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="77"/>
        <source>PNG images (*.png)</source>
        <translation>PNG 画像 (*.png)</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="81"/>
        <source>Export forces as CSV</source>
        <translation>力を CSV で出力</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="81"/>
        <source>CSV files (*.csv)</source>
        <translation>CSV ファイル (*.csv)</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="88"/>
        <source>|F| vs time</source>
        <translation>|F| と時間</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="89"/>
        <source>Fz vs time</source>
        <translation>Fz と時間</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="90"/>
        <source>Fz vs x (Fig. 6)</source>
        <translation>Fz と x（図 6）</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="91"/>
        <source>Force magnitude per finger (N)</source>
        <translation>指ごとの力の大きさ (N)</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="92"/>
        <source>Fz per finger (N)</source>
        <translation>指ごとの Fz (N)</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="93"/>
        <source>Fz (N) against finger x (m)</source>
        <translation>指の x 位置 (m) に対する Fz (N)</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="100"/>
        <source>Resume</source>
        <translation>再開</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="100"/>
        <source>Pause</source>
        <translation>一時停止</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="101"/>
        <source>Export PNG...</source>
        <translation>PNG 出力...</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="102"/>
        <source>Export CSV...</source>
        <translation>CSV 出力...</translation>
    </message>
</context>
<context>
    <name>palpation::ui::MainWindow</name>
    <message>
        <location filename="../ui/main_window.cpp" line="98"/>
        <source>Mouse palpation: move over the breast; the wheel or a downward drag presses the fingertip in.</source>
        <translation>マウス触診: 乳房の上で動かします。ホイールまたは下向きのドラッグで指先を押し込みます。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="108"/>
        <source>No element lies inside that shape: nothing added.</source>
        <translation>その形状の中に要素がありません。追加されませんでした。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="152"/>
        <source>Save screenshot</source>
        <translation>スクリーンショットを保存</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="152"/>
        <source>PNG images (*.png)</source>
        <translation>PNG 画像 (*.png)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="182"/>
        <location filename="../ui/main_window.cpp" line="255"/>
        <source>Stereo</source>
        <translation>立体視</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="192"/>
        <source>Eye separation</source>
        <translation>眼間距離</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="192"/>
        <source>Eye angle (degrees):</source>
        <translation>視差角（度）:</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="244"/>
        <source>Palpation Trainer</source>
        <translation>触診トレーナー</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="245"/>
        <source>&amp;File</source>
        <translation>ファイル(&amp;F)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="246"/>
        <source>Save &amp;screenshot...</source>
        <translation>スクリーンショットを保存(&amp;S)...</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="247"/>
        <source>&amp;Quit</source>
        <translation>終了(&amp;Q)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="248"/>
        <source>&amp;Edit</source>
        <translation>編集(&amp;E)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="249"/>
        <source>Undo</source>
        <translation>元に戻す</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="250"/>
        <source>Redo</source>
        <translation>やり直し</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="251"/>
        <source>&amp;View</source>
        <translation>表示(&amp;V)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="252"/>
        <source>Camera</source>
        <translation>カメラ</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="253"/>
        <source>Oblique</source>
        <translation>斜め</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="253"/>
        <source>Top</source>
        <translation>上</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="253"/>
        <source>Side</source>
        <translation>側面</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="253"/>
        <source>Front</source>
        <translation>正面</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="256"/>
        <source>Mono</source>
        <translation>モノ</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="256"/>
        <source>Anaglyph (red/cyan)</source>
        <translation>アナグリフ（赤/シアン）</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="256"/>
        <source>Side by side</source>
        <translation>サイドバイサイド</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="256"/>
        <source>Interlaced</source>
        <translation>インターレース</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="256"/>
        <source>Quad-buffer (shutter glasses)</source>
        <translation>クアッドバッファ（シャッターメガネ）</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="258"/>
        <source>Eye separation...</source>
        <translation>眼間距離...</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="259"/>
        <source>Mirrored (half-mirror display)</source>
        <translation>鏡像（ハーフミラー表示）</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="260"/>
        <source>Displacement colour map</source>
        <translation>変位カラーマップ</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="261"/>
        <source>Show tumours</source>
        <translation>腫瘍を表示</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="262"/>
        <source>Panels</source>
        <translation>パネル</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="263"/>
        <source>&amp;Mode</source>
        <translation>モード(&amp;M)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="264"/>
        <source>Trainee mode</source>
        <translation>研修生モード</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="265"/>
        <source>Instructor mode</source>
        <translation>指導者モード</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="266"/>
        <source>Tools</source>
        <translation>ツール</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="267"/>
        <source>Camera / scripted hand</source>
        <translation>カメラ / 自動触診ハンド</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="268"/>
        <source>Palpate with the mouse</source>
        <translation>マウスで触診</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="269"/>
        <source>Patient</source>
        <translation>患者</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="270"/>
        <source>Tumours</source>
        <translation>腫瘍</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="271"/>
        <source>Forces</source>
        <translation>力</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="272"/>
        <source>Simulation</source>
        <translation>シミュレーション</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="273"/>
        <source>Device</source>
        <translation>デバイス</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="335"/>
        <source>%1 nodes, %2 tetrahedra</source>
        <translation>節点 %1、四面体 %2</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="368"/>
        <source>Backend: %1</source>
        <translation>バックエンド: %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="369"/>
        <source>Simulation: %1 Hz</source>
        <translation>シミュレーション: %1 Hz</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="370"/>
        <source>Haptic: %1 Hz</source>
        <translation>力覚: %1 Hz</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="372"/>
        <source>mouse</source>
        <translation>マウス</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="373"/>
        <source>simulated HandHIRO</source>
        <translation>シミュレーションの HandHIRO</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="374"/>
        <source>Device: %1, %2</source>
        <translation>デバイス: %1、%2</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="374"/>
        <source>connected</source>
        <translation>接続中</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="374"/>
        <source>not connected</source>
        <translation>未接続</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="375"/>
        <source>View: %1 fps</source>
        <translation>表示: %1 fps</translation>
    </message>
</context>
<context>
    <name>palpation::ui::PatientPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="68"/>
        <source>Breast phantom (paper)</source>
        <translation>乳房ファントム（論文）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="69"/>
        <source>Box phantom</source>
        <translation>直方体ファントム</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="70"/>
        <source>Coarse (about 1,000 nodes, real time on a CPU)</source>
        <translation>粗い（約 1,000 節点、CPU でリアルタイム）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="71"/>
        <source>Paper (about 9,100 nodes, GPU)</source>
        <translation>論文（約 9,100 節点、GPU）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="72"/>
        <source>Fine (GPU)</source>
        <translation>細かい（GPU）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="73"/>
        <source>Patient</source>
        <translation>患者</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="74"/>
        <source>Resolution</source>
        <translation>解像度</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="75"/>
        <source>Tissue Young&apos;s modulus</source>
        <translation>組織のヤング率</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="76"/>
        <source>Poisson ratio</source>
        <translation>ポアソン比</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="77"/>
        <source>Load patient</source>
        <translation>患者を読み込む</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="78"/>
        <source>Built-in phantoms; the patient library comes with a later version.</source>
        <translation>組み込みファントム。患者ライブラリは今後のバージョンで追加されます。</translation>
    </message>
</context>
<context>
    <name>palpation::ui::SimulationPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="272"/>
        <source>Backend</source>
        <translation>バックエンド</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="273"/>
        <source>CG tolerance</source>
        <translation>CG 許容誤差</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="274"/>
        <source>CG max. iterations</source>
        <translation>CG 最大反復回数</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="275"/>
        <source>State</source>
        <translation>状態</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="276"/>
        <source>Step time</source>
        <translation>ステップ時間</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="277"/>
        <source>CG iterations</source>
        <translation>CG 反復回数</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="278"/>
        <source>Simulation rate</source>
        <translation>シミュレーション周波数</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="279"/>
        <source>Haptic rate</source>
        <translation>力覚ループ周波数</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="280"/>
        <source>Apply solver settings</source>
        <translation>ソルバー設定を適用</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="281"/>
        <source>A backend change takes effect when the patient is (re)loaded.</source>
        <translation>バックエンドの変更は患者の（再）読み込み時に反映されます。</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="291"/>
        <source>%1 ms</source>
        <translation>%1 ms</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="293"/>
        <location filename="../ui/panels.cpp" line="294"/>
        <source>%1 Hz</source>
        <translation>%1 Hz</translation>
    </message>
</context>
<context>
    <name>palpation::ui::TumourEditor</name>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="11"/>
        <source>Tumour (paper, 107 kPa)</source>
        <translation>腫瘍（論文、107 kPa）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="11"/>
        <source>Ueda et al., paper section 4.1</source>
        <translation>上田ら、論文 4.1 節</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="12"/>
        <source>Invasive ductal carcinoma (Krouskop, 5%)</source>
        <translation>浸潤性乳管癌（Krouskop、5%）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="12"/>
        <source>Krouskop et al. 1998: 93-112 kPa at 5% precompression</source>
        <translation>Krouskop ら 1998: 5% 予圧縮で 93-112 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="13"/>
        <source>Invasive ductal carcinoma (Krouskop, 20%)</source>
        <translation>浸潤性乳管癌（Krouskop、20%）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="13"/>
        <source>Krouskop et al. 1998: 460-558 kPa at 20% precompression</source>
        <translation>Krouskop ら 1998: 20% 予圧縮で 460-558 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="14"/>
        <source>Fibrous tissue (Krouskop, 5%)</source>
        <translation>線維組織（Krouskop、5%）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="14"/>
        <source>Krouskop et al. 1998: 96-116 kPa at 5% precompression</source>
        <translation>Krouskop ら 1998: 5% 予圧縮で 96-116 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="15"/>
        <source>DCIS (Krouskop, 20%)</source>
        <translation>DCIS（Krouskop、20%）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="15"/>
        <source>Krouskop et al. 1998: 291-307 kPa at 20% precompression</source>
        <translation>Krouskop ら 1998: 20% 予圧縮で 291-307 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="16"/>
        <source>Fibroglandular (Krouskop, 5%)</source>
        <translation>線維腺組織（Krouskop、5%）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="16"/>
        <source>Krouskop et al. 1998: 28-35 kPa at 5% precompression</source>
        <translation>Krouskop ら 1998: 5% 予圧縮で 28-35 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="17"/>
        <source>IDC high grade (Samani)</source>
        <translation>高悪性度 IDC（Samani）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="17"/>
        <source>Samani et al. 2007: 10-43 kPa by grade, small strain</source>
        <translation>Samani ら 2007: 悪性度により 10-43 kPa、微小ひずみ</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="18"/>
        <source>Fibroadenoma (Samani, 2x fat)</source>
        <translation>線維腺腫（Samani、脂肪の 2 倍）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="18"/>
        <source>Samani et al. 2007: about 6.4 kPa</source>
        <translation>Samani ら 2007: 約 6.4 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="71"/>
        <source>Patient&apos;s tumour</source>
        <translation>患者の腫瘍</translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/tumour_editor.cpp" line="78"/>
        <source>%1 (%n elements)</source>
        <translation><numerusform>%1（%n 要素）</numerusform></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="120"/>
        <source>%1 at (%2, %3, %4) cm, %5 kPa</source>
        <translation>%1 (%2, %3, %4) cm、%5 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="121"/>
        <source>Sphere</source>
        <translation>球</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="121"/>
        <source>Ellipsoid</source>
        <translation>楕円体</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="126"/>
        <source>Add tumour: %1</source>
        <translation>腫瘍を追加: %1</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="139"/>
        <source>Remove tumour: %1</source>
        <translation>腫瘍を削除: %1</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="164"/>
        <source>Erase</source>
        <translation>消去</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="164"/>
        <source>Paint</source>
        <translation>描画</translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/tumour_editor.cpp" line="177"/>
        <source>Erase stroke (%n elements)</source>
        <translation><numerusform>消去ストローク（%n 要素）</numerusform></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/tumour_editor.cpp" line="180"/>
        <source>Paint stroke (%n elements)</source>
        <translation><numerusform>描画ストローク（%n 要素）</numerusform></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="181"/>
        <source>Painted tumour %1, %2 kPa</source>
        <translation>描画した腫瘍 %1、%2 kPa</translation>
    </message>
</context>
<context>
    <name>palpation::ui::TumourPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="186"/>
        <location filename="../ui/panels.cpp" line="212"/>
        <source>Source: %1</source>
        <translation>出典: %1</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="213"/>
        <source>Preset</source>
        <translation>プリセット</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="214"/>
        <source>Stiffness</source>
        <translation>硬さ</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="215"/>
        <source>Add by shape</source>
        <translation>形状で追加</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="216"/>
        <source>Sphere</source>
        <translation>球</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="217"/>
        <source>Ellipsoid</source>
        <translation>楕円体</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="218"/>
        <source>Shape</source>
        <translation>形状</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="219"/>
        <source>Centre x, y, z</source>
        <translation>中心 x, y, z</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="220"/>
        <source>Radius (x, y, z)</source>
        <translation>半径 (x, y, z)</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="221"/>
        <source>Add tumour</source>
        <translation>腫瘍を追加</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="222"/>
        <source>Remove selected</source>
        <translation>選択を削除</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="223"/>
        <source>Brush</source>
        <translation>ブラシ</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="224"/>
        <source>Radius</source>
        <translation>半径</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="225"/>
        <source>Depth below the skin</source>
        <translation>皮膚からの深さ</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="226"/>
        <source>Paint</source>
        <translation>描画</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="227"/>
        <source>Erase</source>
        <translation>消去</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="228"/>
        <source>Drag on the breast to paint tumour tissue (one undo step per stroke)</source>
        <translation>乳房上をドラッグして腫瘍組織を描画（1 ストロークで 1 回の取り消し）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="229"/>
        <source>Drag on the breast to restore healthy tissue</source>
        <translation>乳房上をドラッグして正常組織に戻す</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="230"/>
        <source>Undo</source>
        <translation>元に戻す</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="231"/>
        <source>Redo</source>
        <translation>やり直し</translation>
    </message>
</context>
<context>
    <name>palpation::ui::VtkView</name>
    <message>
        <location filename="../ui/vtk_view.cpp" line="287"/>
        <source>Quad-buffer stereo is not available: this display&apos;s OpenGL context has no stereo buffers (needs a stereo-capable GPU, driver and display). Use anaglyph, side-by-side or interlaced.</source>
        <translation>クアッドバッファ立体視は使用できません。このディスプレイの OpenGL コンテキストにステレオバッファがありません（立体視対応の GPU、ドライバ、ディスプレイが必要です）。アナグリフ、サイドバイサイド、インターレースを使用してください。</translation>
    </message>
</context>
</TS>
